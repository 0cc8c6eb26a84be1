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
0.00256233 0.104493
0.00504863 0.0463784
0.0100346 0.0412629
0.0199399 0.0426167
EOD
$d1 << EOD
0.00986843 0.0478461
0.019659 0.04919
0.039112 0.0448712
0.0784375 0.0430324
EOD
$d2 << EOD
0.00558822 0.104493
0.0110765 0.0463784
0.0220932 0.0412629
0.0441409 0.0426167
EOD
$d3 << EOD
0.0637563 0.0166993
0.0270363 0.000689941
0.0246026 5.04913e-05
EOD
$d4 << EOD
0.0259758 0.000230517
0.0686569 9.71797e-06
0.14082 5.06967e-06
EOD
$d5 << EOD
0.00493728 0.0442913
0.00951418 0.0067155
0.0236298 0.000158706
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk Verlet' noenhanced
