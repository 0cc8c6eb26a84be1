set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'satellite_stiffness.svg'
set title 'Satellite, tol 1e-6: CPU time vs internal stiffness'
set xlabel 'internal stiffness [N/m]'
set ylabel 'CPU time [s]'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
10000 0.0205372
100000 0.0829298
1e+06 0.293048
1e+07 0.963226
1e+08 3.03369
EOD
$d1 << EOD
10000 0.00347961
100000 0.0121055
1e+06 0.0399698
1e+07 0.125232
1e+08 0.41725
EOD
$d2 << EOD
10000 0.00592793
10000 0.0114095
10000 0.0228572
10000 0.0248927
10000 0.0307587
10000 0.0327148
10000 0.0357512
100000 0.0039227
100000 0.00465254
100000 0.00855067
100000 0.0227594
100000 0.0619572
100000 0.0720775
100000 0.084027
1e+06 0.00375977
1e+06 0.00378244
1e+06 0.0042931
1e+06 0.00697286
1e+06 0.0144908
1e+06 0.039171
1e+06 0.0989862
1e+07 0.00533606
1e+07 0.00640124
1e+07 0.00461245
1e+07 0.00548796
1e+07 0.00650046
1e+07 0.0113906
1e+07 0.0244045
1e+08 0.0105474
1e+08 0.00964037
1e+08 0.011195
1e+08 0.00679913
1e+08 0.00724433
1e+08 0.00869406
1e+08 0.0114047
EOD
$d3 << EOD
10000 0.0135111
100000 0.0223583
1e+06 0.033387
1e+07 0.053415
1e+08 0.10627
EOD
$d4 << EOD
10000 0.0263184
100000 0.0606113
1e+06 0.122828
1e+07 0.259672
1e+08 0.472383
EOD
$d5 << EOD
10000 0.000899702
100000 0.00287335
1e+06 0.00918654
1e+07 0.0272775
1e+08 0.100963
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
