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
0.00241117 0.104493
0.00477408 0.0463784
0.00980994 0.0412629
0.0191299 0.0426167
EOD
$d1 << EOD
0.00935743 0.0478461
0.0187532 0.04919
0.0380193 0.0448712
0.0767018 0.0430324
EOD
$d2 << EOD
0.00532399 0.104493
0.0106303 0.0463784
0.0211449 0.0412629
0.0430064 0.0426167
EOD
$d3 << EOD
0.0560958 0.0166993
0.0235374 0.000689941
0.0213388 5.04913e-05
EOD
$d4 << EOD
0.0223921 0.000230517
0.0591906 9.71797e-06
0.120383 5.06967e-06
EOD
$d5 << EOD
0.00443257 0.0442913
0.00853478 0.0067155
0.0214228 0.000138032
0.00441745 0.000299808
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk Verlet' noenhanced
