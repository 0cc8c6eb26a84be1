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
0.00178088 0.104493
0.00353025 0.0463784
0.00702113 0.0412629
0.0139595 0.0426167
EOD
$d1 << EOD
0.00697382 0.0478461
0.0138496 0.04919
0.0274378 0.0448712
0.0550049 0.0430324
EOD
$d2 << EOD
0.00408674 0.104493
0.00814653 0.0463784
0.0162046 0.0412629
0.032467 0.0426167
EOD
$d3 << EOD
0.0420907 0.0166993
0.0180199 0.000689941
0.0162958 5.04913e-05
EOD
$d4 << EOD
0.0171625 0.000230517
0.0450194 9.71797e-06
0.0920892 5.06967e-06
EOD
$d5 << EOD
0.013726 8.95685e-05
EOD
$d6 << EOD
0.00343754 0.0442913
0.00660835 0.0067155
0.0164726 0.000138032
0.00343305 0.000299808
EOD
$d7 << EOD
0.00219768 0.00863488
0.00219676 0.00035648
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk RODAS4 (state norm), rigid body' noenhanced, $d6 using 1:2 with linespoints title 'pronk Verlet' noenhanced, $d7 using 1:2 with linespoints title 'pronk Verlet, rigid body' noenhanced
