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
0.00265986 0.104493
0.00519225 0.0463784
0.0100602 0.0412629
0.0200207 0.0426167
EOD
$d1 << EOD
0.00993101 0.0478461
0.0197695 0.04919
0.0396783 0.0448712
0.0799689 0.0430324
EOD
$d2 << EOD
0.00561976 0.104493
0.0111639 0.0463784
0.0222274 0.0412629
0.0443579 0.0426167
EOD
$d3 << EOD
0.0745014 0.0166993
0.0346643 0.000689941
0.0293421 5.04913e-05
EOD
$d4 << EOD
0.030716 0.000230517
0.0796469 9.71797e-06
0.167111 5.06967e-06
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced
