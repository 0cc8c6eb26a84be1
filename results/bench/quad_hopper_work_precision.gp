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
0.00257792 0.104493
0.00511909 0.0463784
0.0101263 0.0412629
0.0200616 0.0426167
EOD
$d1 << EOD
0.00995178 0.0478461
0.0198421 0.04919
0.0398556 0.0448712
0.0793761 0.0430324
EOD
$d2 << EOD
0.00560734 0.104493
0.0112469 0.0463784
0.0224117 0.0412629
0.0447075 0.0426167
EOD
$d3 << EOD
0.109649 0.0143577
0.041449 0.00457081
0.0509316 7.34356e-05
EOD
$d4 << EOD
0.0371232 0.000230221
0.138611 2.51262e-05
0.336663 1.784e-06
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced
