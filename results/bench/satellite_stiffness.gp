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
10000 0.0304135
100000 0.124263
1e+06 0.440938
1e+07 1.41927
1e+08 4.5556
EOD
$d1 << EOD
10000 0.00359599
100000 0.0120798
1e+06 0.041434
1e+07 0.138168
1e+08 0.443279
EOD
$d2 << EOD
10000 0.00657026
10000 0.0251652
10000 0.0319182
10000 0.0394789
100000 0.00447282
100000 0.00929693
100000 0.0663035
100000 0.0894233
1e+06 0.00433736
1e+06 0.00495304
1e+06 0.0165463
1e+06 0.112261
1e+07 0.00640977
1e+07 0.00547558
1e+07 0.00791056
1e+07 0.0276236
1e+08 0.0120276
1e+08 0.0128174
1e+08 0.00816912
1e+08 0.0130662
EOD
$d3 << EOD
10000 0.0146018
100000 0.0234387
1e+06 0.0362384
1e+07 0.0600938
1e+08 0.118485
EOD
$d4 << EOD
10000 0.0287272
100000 0.0643219
1e+06 0.130762
1e+07 0.309315
1e+08 0.51466
EOD
$d5 << EOD
10000 0.00117881
100000 0.00370252
1e+06 0.0118522
1e+07 0.0366983
1e+08 0.117111
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
