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
0.000435588 3.17542e-09
0.000434146 3.17545e-09
0.000429834 3.1754e-09
0.000435496 3.17546e-09
0.000434244 3.17541e-09
0.000428696 1.08778e-09
0.000436509 1.69325e-10
0.000467444 2.25749e-11
EOD
$d1 << EOD
0.000672162 0.00252364
0.000675435 0.00123205
0.00093919 0.000609355
0.00146244 0.000303181
0.00255139 0.000151231
0.0047593 7.56063e-05
EOD
$d2 << EOD
0.000622134 8.59263e-07
0.0008075 2.15147e-07
0.001134 5.38298e-08
0.00188838 1.34629e-08
0.00331725 3.36639e-09
0.00622952 8.41584e-10
EOD
$d3 << EOD
0.000436619 9.76131e-08
0.000469562 7.3024e-09
0.000521429 4.5635e-10
0.00068846 2.84614e-11
0.000903954 1.72726e-12
0.00143304 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
