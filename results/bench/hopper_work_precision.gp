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
0.00035516 3.17542e-09
0.000356422 3.17545e-09
0.000354479 3.1754e-09
0.000390072 3.17546e-09
0.000355881 3.17541e-09
0.000359346 1.08778e-09
0.000360909 1.69325e-10
0.000367878 2.25749e-11
EOD
$d1 << EOD
0.000518243 0.00252364
0.000511623 0.00123205
0.000698883 0.000609355
0.00106965 0.000303181
0.0018233 0.000151231
0.00323707 7.56063e-05
EOD
$d2 << EOD
0.00045573 8.59263e-07
0.000582419 2.15147e-07
0.000833693 5.38298e-08
0.0013597 1.34629e-08
0.0023233 3.36639e-09
0.00439228 8.41584e-10
EOD
$d3 << EOD
0.000346808 9.76131e-08
0.000374999 7.3024e-09
0.000409501 4.5635e-10
0.000500847 2.84614e-11
0.000702868 1.72726e-12
0.00103132 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
