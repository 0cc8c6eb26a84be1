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
10000 0.0399537
100000 0.163334
1e+06 0.565426
1e+07 1.8637
1e+08 5.86699
EOD
$d1 << EOD
10000 0.00486239
100000 0.0163995
1e+06 0.0554686
1e+07 0.181345
1e+08 0.583811
EOD
$d2 << EOD
10000 0.0548617
100000 0.123774
1e+06 0.169473
1e+07 0.119207
1e+08 0.188207
EOD
$d3 << EOD
10000 0.0210427
100000 0.0330974
1e+06 0.0510602
1e+07 0.0852508
1e+08 0.164404
EOD
$d4 << EOD
10000 0.0405747
100000 0.0920584
1e+06 0.18768
1e+07 0.393839
1e+08 0.723805
EOD
$d5 << EOD
10000 0.00134364
100000 0.00417046
1e+06 0.0131396
1e+07 0.0414458
1e+08 0.13216
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
