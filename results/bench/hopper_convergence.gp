set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'hopper_convergence.svg'
set title 'Fixed-step methods on the hopper: error vs step'
set xlabel 'step h [s]'
set ylabel 'final CoM position error [m]'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.004 0.00252364
0.002 0.00123205
0.001 0.000609355
0.0005 0.000303181
0.00025 0.000151231
0.000125 7.56063e-05
EOD
$d1 << EOD
0.004 8.59263e-07
0.002 2.15147e-07
0.001 5.38298e-08
0.0005 1.34629e-08
0.00025 3.36639e-09
0.000125 8.41584e-10
EOD
$d2 << EOD
0.04 9.76131e-08
0.02 7.3024e-09
0.01 4.5635e-10
0.005 2.84614e-11
0.0025 1.72726e-12
0.00125 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'euler' noenhanced, $d1 using 1:2 with linespoints title 'rk2' noenhanced, $d2 using 1:2 with linespoints title 'rk4' noenhanced
