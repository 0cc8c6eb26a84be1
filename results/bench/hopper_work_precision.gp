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
0.000476909 3.17542e-09
0.000429165 3.17545e-09
0.00042996 3.1754e-09
0.00046524 3.17546e-09
0.00043038 3.17541e-09
0.00042804 1.08778e-09
0.000472771 1.69325e-10
0.000440928 2.25749e-11
EOD
$d1 << EOD
0.000793318 0.00252364
0.000707248 0.00123205
0.000983429 0.000609355
0.00146442 0.000303181
0.00250347 0.000151231
0.00450464 7.56063e-05
EOD
$d2 << EOD
0.000645663 8.59263e-07
0.000820646 2.15147e-07
0.00116857 5.38298e-08
0.00187817 1.34629e-08
0.00327941 3.36639e-09
0.00625952 8.41584e-10
EOD
$d3 << EOD
0.000469727 9.76131e-08
0.00051634 7.3024e-09
0.000551422 4.5635e-10
0.000683892 2.84614e-11
0.000930818 1.72726e-12
0.00148691 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
