set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'quad_hopper_work_precision.svg'
set title 'Quad spring hopper drop (undamped): energy error vs cost'
set xlabel 'CPU time per simulated second [s/s]'
set ylabel 'energy error / drop energy'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.0019095 0.104493
0.00368512 0.0463784
0.00743306 0.0412629
0.0146487 0.0426167
EOD
$d1 << EOD
0.00708947 0.0478461
0.0148366 0.04919
0.0283879 0.0448712
0.0565524 0.0430324
EOD
$d2 << EOD
0.0037363 0.104493
0.00745292 0.0463784
0.0148192 0.0412629
0.0300432 0.0426167
EOD
$d3 << EOD
0.519674 0.236478
0.760614 0.00554343
1.28572 0.000617775
EOD
$d4 << EOD
0.573645 0.0407434
1.02823 0.00312587
1.70366 0.000228606
0.0589658 0.020701
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced
