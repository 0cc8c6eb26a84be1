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
0.00219406 0.104493
0.00430194 0.0463784
0.00841799 0.0412629
0.0167264 0.0426167
EOD
$d1 << EOD
0.00821293 0.0478461
0.016305 0.04919
0.033611 0.0448712
0.0653502 0.0430324
EOD
$d2 << EOD
0.00448965 0.104493
0.00893232 0.0463784
0.0176839 0.0412629
0.0352711 0.0426167
EOD
$d3 << EOD
0.633594 0.236478
0.939091 0.00554343
1.58402 0.000617775
EOD
$d4 << EOD
0.706194 0.0407434
1.23727 0.00312587
2.10079 0.000228606
0.0876089 0.020701
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced
