set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'quad_hopper_work_precision.svg'
set title 'Quad spring hopper drop: energy error vs cost'
set xlabel 'CPU time per simulated second [s/s]'
set ylabel 'energy error / drop energy'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.00255264 0.104493
0.00505444 0.0463784
0.0100636 0.0412629
0.0199717 0.0426167
EOD
$d1 << EOD
0.00992703 0.0478461
0.0197447 0.04919
0.0393536 0.0448712
0.0789004 0.0430324
EOD
$d2 << EOD
0.00559221 0.104493
0.0111295 0.0463784
0.0222517 0.0412629
0.0443826 0.0426167
EOD
$d3 << EOD
0.0592866 0.0166993
0.0252737 0.000689941
0.0242252 5.04913e-05
EOD
$d4 << EOD
0.0241794 0.000230517
0.0642328 9.71797e-06
0.130204 5.06967e-06
EOD
$d5 << EOD
0.00448226 0.0442913
0.00849694 0.0067155
0.0210172 0.000158706
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk Verlet' noenhanced
