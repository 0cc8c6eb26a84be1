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
0.000424444 3.17542e-09
0.000453643 3.17545e-09
0.000402389 3.1754e-09
0.000409562 3.17546e-09
0.000406613 3.17541e-09
0.000431114 1.08778e-09
0.000374886 1.69325e-10
0.000402005 2.25749e-11
EOD
$d1 << EOD
0.000653806 0.00252364
0.000639252 0.00123205
0.000905746 0.000609355
0.00127883 0.000303181
0.00213501 0.000151231
0.00384028 7.56063e-05
EOD
$d2 << EOD
0.000555351 8.59263e-07
0.00066446 2.15147e-07
0.00102829 5.38298e-08
0.00158977 1.34629e-08
0.00278238 3.36639e-09
0.00500384 8.41584e-10
EOD
$d3 << EOD
0.00035895 9.76131e-08
0.000423371 7.3024e-09
0.000462054 4.5635e-10
0.000580774 2.84614e-11
0.000764987 1.72726e-12
0.00130559 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
