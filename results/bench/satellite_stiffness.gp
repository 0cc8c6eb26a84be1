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
10000 0.0403489
100000 0.164995
1e+06 0.569298
1e+07 1.86994
1e+08 5.8942
EOD
$d1 << EOD
10000 0.00459826
100000 0.0155991
1e+06 0.0535819
1e+07 0.172302
1e+08 0.563012
EOD
$d2 << EOD
10000 0.0538838
100000 0.122251
1e+06 0.170096
1e+07 0.120868
1e+08 0.186024
EOD
$d3 << EOD
10000 0.0201834
100000 0.0326121
1e+06 0.0501746
1e+07 0.0821143
1e+08 0.159066
EOD
$d4 << EOD
10000 0.0391307
100000 0.0884089
1e+06 0.179869
1e+07 0.379816
1e+08 0.703062
EOD
$d5 << EOD
10000 0.0012891
100000 0.00398002
1e+06 0.0124117
1e+07 0.0395257
1e+08 0.124985
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
