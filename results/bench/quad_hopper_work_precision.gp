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
0.0016797 0.104493
0.00332916 0.0463784
0.00643166 0.0412629
0.0126977 0.0426167
EOD
$d1 << EOD
0.00631059 0.0478461
0.0127827 0.04919
0.0250437 0.0448712
0.0511038 0.0430324
EOD
$d2 << EOD
0.00336864 0.104493
0.00674502 0.0463784
0.0133782 0.0412629
0.0268287 0.0426167
EOD
$d3 << EOD
0.0323186 0.0112304
0.0124116 0.00122208
0.0146464 6.64626e-05
EOD
$d4 << EOD
0.0157082 0.000190247
0.0416352 1.81686e-05
0.0840381 4.12843e-06
EOD
$d5 << EOD
0.0109232 9.39806e-05
EOD
$d6 << EOD
0.00326271 0.044291
0.00624016 0.0067155
0.0154864 0.000138032
0.00322686 0.000299808
EOD
$d7 << EOD
0.00161988 0.00863488
0.00164331 0.00035648
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'pronk RODAS4 (state norm), rigid body' noenhanced, $d6 using 1:2 with linespoints title 'pronk Verlet' noenhanced, $d7 using 1:2 with linespoints title 'pronk Verlet, rigid body' noenhanced
