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
0.00167859 0.104493
0.00337022 0.0463784
0.00665261 0.0412629
0.0130176 0.0426167
EOD
$d1 << EOD
0.0064832 0.0478461
0.0128865 0.04919
0.0256168 0.0448712
0.0513286 0.0430324
EOD
$d2 << EOD
0.00339454 0.104493
0.0067037 0.0463784
0.0133339 0.0412629
0.0266156 0.0426167
EOD
$d3 << EOD
0.0380533 0.0166993
0.0162725 0.000689941
0.0144108 5.04913e-05
EOD
$d4 << EOD
0.0158953 0.000230517
0.0407723 9.71797e-06
0.0834068 5.06967e-06
EOD
$d5 << EOD
0.0124284 8.95685e-05
EOD
$d6 << EOD
0.00338212 0.0442913
0.00655085 0.0067155
0.0164386 0.000138032
0.00329043 0.000299808
EOD
$d7 << EOD
0.00217736 0.00863488
0.00224436 0.00035648
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk RODAS4 (state norm), rigid body' noenhanced, $d6 using 1:2 with linespoints title 'pronk Verlet' noenhanced, $d7 using 1:2 with linespoints title 'pronk Verlet, rigid body' noenhanced
