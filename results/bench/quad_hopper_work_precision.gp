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
0.00250402 0.104493
0.00498671 0.0463784
0.0100512 0.0412629
0.019754 0.0426167
EOD
$d1 << EOD
0.00981437 0.0478461
0.019545 0.04919
0.0393381 0.0448712
0.0791468 0.0430324
EOD
$d2 << EOD
0.00560842 0.104493
0.0111048 0.0463784
0.0218468 0.0412629
0.0437564 0.0426167
EOD
$d3 << EOD
0.0585229 0.0166993
0.0243603 0.000689941
0.02203 5.04913e-05
EOD
$d4 << EOD
0.0240578 0.000230517
0.0620889 9.71797e-06
0.127863 5.06967e-06
EOD
$d5 << EOD
0.00437404 0.0442913
0.00853036 0.0067155
0.0210547 0.000138032
0.0044044 0.000301107
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk Verlet' noenhanced
