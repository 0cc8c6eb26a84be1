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
0.000567101 3.17542e-09
0.000459013 3.17545e-09
0.000439726 3.1754e-09
0.000466393 3.17546e-09
0.000439582 3.17541e-09
0.000435353 1.08778e-09
0.000446915 1.69325e-10
0.000449593 2.25749e-11
EOD
$d1 << EOD
0.000708711 0.00252364
0.00066974 0.00123205
0.00097485 0.000609355
0.0014452 0.000303181
0.00378286 0.000151231
0.00457181 7.56063e-05
EOD
$d2 << EOD
0.000649846 8.59263e-07
0.000804985 2.15147e-07
0.00112725 5.38298e-08
0.00186405 1.34629e-08
0.00324907 3.36639e-09
0.00637699 8.41584e-10
EOD
$d3 << EOD
0.000532789 9.76131e-08
0.00051613 7.3024e-09
0.000589861 4.5635e-10
0.000757588 2.84614e-11
0.00119459 1.72726e-12
0.00174929 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
