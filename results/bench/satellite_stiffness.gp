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
10000 0.038073
100000 0.156029
1e+06 0.534488
1e+07 1.78051
1e+08 5.63821
EOD
$d1 << EOD
10000 0.0045496
100000 0.0154146
1e+06 0.0528958
1e+07 0.169307
1e+08 0.524835
EOD
$d2 << EOD
10000 0.0521883
100000 0.119373
1e+06 0.159219
1e+07 0.11196
1e+08 0.178059
EOD
$d3 << EOD
10000 0.0207745
100000 0.0312492
1e+06 0.0495878
1e+07 0.079795
1e+08 0.151451
EOD
$d4 << EOD
10000 0.0388876
100000 0.0832386
1e+06 0.177342
1e+07 0.369226
1e+08 0.67566
EOD
$d5 << EOD
10000 0.00150206
100000 0.00454187
1e+06 0.0138464
1e+07 0.0435408
1e+08 0.132718
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
