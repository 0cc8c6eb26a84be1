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
0.00167876 0.104493
0.00329211 0.0463784
0.00654605 0.0412629
0.0130214 0.0426167
EOD
$d1 << EOD
0.00632429 0.0478461
0.0127819 0.04919
0.0257074 0.0448712
0.0512074 0.0430324
EOD
$d2 << EOD
0.00336554 0.104493
0.00659801 0.0463784
0.0132768 0.0412629
0.0264428 0.0426167
EOD
$d3 << EOD
0.0313609 0.0112304
0.0121563 0.00122208
0.0146051 6.64626e-05
EOD
$d4 << EOD
0.0153482 0.000190247
0.0405258 1.81686e-05
0.0802678 4.12843e-06
EOD
$d5 << EOD
0.0107101 9.39806e-05
EOD
$d6 << EOD
0.00309828 0.044291
0.00596561 0.0067155
0.0150154 0.000138032
0.00309462 0.000299808
EOD
$d7 << EOD
0.00151061 0.00863488
0.00155528 0.00035648
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk RODAS4 (state norm), rigid body' noenhanced, $d6 using 1:2 with linespoints title 'pronk Verlet' noenhanced, $d7 using 1:2 with linespoints title 'pronk Verlet, rigid body' noenhanced
