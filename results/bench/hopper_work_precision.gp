set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'hopper_work_precision.svg'
set title 'Reduced legged pulse hopper: final CoM error vs CPU time'
set xlabel 'CPU time [s]'
set ylabel 'final CoM position error [m]'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.000435158 3.17542e-09
0.0004281 3.17545e-09
0.000429753 3.1754e-09
0.000430995 3.17546e-09
0.000427883 3.17541e-09
0.000427764 1.08778e-09
0.000431094 1.69325e-10
0.000439515 2.25749e-11
EOD
$d1 << EOD
0.000631239 0.00252364
0.000704254 0.00123205
0.000925304 0.000609355
0.001436 0.000303181
0.00244345 0.000151231
0.00441635 7.56063e-05
EOD
$d2 << EOD
0.00058043 8.59263e-07
0.000763369 2.15147e-07
0.0011296 5.38298e-08
0.00182397 1.34629e-08
0.003276 3.36639e-09
0.00610944 8.41584e-10
EOD
$d3 << EOD
0.000421951 9.76131e-08
0.000462289 7.3024e-09
0.000514115 4.5635e-10
0.000678435 2.84614e-11
0.000896349 1.72726e-12
0.0014609 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
