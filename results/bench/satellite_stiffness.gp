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
10000 0.025277
100000 0.102249
1e+06 0.351319
1e+07 1.1663
1e+08 3.97917
EOD
$d1 << EOD
10000 0.0361525
100000 0.097727
1e+06 0.2976
1e+07 0.952735
1e+08 3.04072
EOD
$d2 << EOD
10000 0.0499478
100000 0.0667296
1e+06 0.102779
1e+07 0.162017
1e+08 0.308158
EOD
$d3 << EOD
10000 0.0910201
100000 0.199802
1e+06 0.392305
1e+07 0.772605
1e+08 1.32844
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced
