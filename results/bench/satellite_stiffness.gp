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
10000 0.0403175
100000 0.168786
1e+06 0.583879
1e+07 2.20099
1e+08 6.13823
EOD
$d1 << EOD
10000 0.00588164
100000 0.0199097
1e+06 0.0691654
1e+07 0.252348
1e+08 0.713467
EOD
$d2 << EOD
10000 0.124454
100000 0.292607
1e+06 0.552036
1e+07 0.295549
1e+08 0.474536
EOD
$d3 << EOD
10000 0.0337471
100000 0.0529023
1e+06 0.086256
1e+07 0.142417
1e+08 0.253973
EOD
$d4 << EOD
10000 0.0650839
100000 0.150465
1e+06 0.301501
1e+07 0.8382
1e+08 1.14263
EOD
$d5 << EOD
10000 0.00147318
100000 0.00485987
1e+06 0.0224438
1e+07 0.0458561
1e+08 0.150772
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
