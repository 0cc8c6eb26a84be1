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
10000 0.0213335
100000 0.0883825
1e+06 0.307458
1e+07 1.19183
1e+08 3.32569
EOD
$d1 << EOD
10000 0.00441065
100000 0.0144195
1e+06 0.0508596
1e+07 0.163902
1e+08 0.692709
EOD
$d2 << EOD
10000 0.0879123
100000 0.202642
1e+06 0.290331
1e+07 0.205609
1e+08 0.329905
EOD
$d3 << EOD
10000 0.0237065
100000 0.0365581
1e+06 0.0581595
1e+07 0.092718
1e+08 0.177347
EOD
$d4 << EOD
10000 0.0465436
100000 0.103034
1e+06 0.204745
1e+07 0.446365
1e+08 0.796997
EOD
$d5 << EOD
10000 0.00118833
100000 0.0037515
1e+06 0.0114531
1e+07 0.0363409
1e+08 0.1425
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
