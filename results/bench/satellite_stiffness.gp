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
10000 0.0398608
100000 0.162493
1e+06 0.548454
1e+07 1.82526
1e+08 5.78325
EOD
$d1 << EOD
10000 0.00487838
100000 0.0163589
1e+06 0.0569494
1e+07 0.182551
1e+08 0.587697
EOD
$d2 << EOD
10000 0.0553706
100000 0.126888
1e+06 0.178681
1e+07 0.120916
1e+08 0.200232
EOD
$d3 << EOD
10000 0.0212202
100000 0.0337885
1e+06 0.0527921
1e+07 0.0870108
1e+08 0.167417
EOD
$d4 << EOD
10000 0.0419617
100000 0.0940769
1e+06 0.19308
1e+07 0.407178
1e+08 0.744411
EOD
$d5 << EOD
10000 0.00155104
100000 0.00493888
1e+06 0.0155388
1e+07 0.0512452
1e+08 0.154473
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
