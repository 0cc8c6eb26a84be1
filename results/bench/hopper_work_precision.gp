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
0.000354935 3.17542e-09
0.000352593 3.17545e-09
0.000351254 3.1754e-09
0.000354055 3.17546e-09
0.000351624 3.17541e-09
0.000347587 1.08778e-09
0.000350416 1.69325e-10
0.000361059 2.25749e-11
EOD
$d1 << EOD
0.000541979 0.00252364
0.000536734 0.00123205
0.000726959 0.000609355
0.0011043 0.000303181
0.00196216 0.000151231
0.00367514 7.56063e-05
EOD
$d2 << EOD
0.000499112 8.59263e-07
0.00065148 2.15147e-07
0.000883462 5.38298e-08
0.00143594 1.34629e-08
0.00255861 3.36639e-09
0.00489767 8.41584e-10
EOD
$d3 << EOD
0.000368835 9.76131e-08
0.000387209 7.3024e-09
0.000414611 4.5635e-10
0.00051467 2.84614e-11
0.000695203 1.72726e-12
0.00108749 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
