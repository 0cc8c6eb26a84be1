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
0.000478281 3.17542e-09
0.000486474 3.17545e-09
0.000538191 3.1754e-09
0.000481907 3.17546e-09
0.000486333 3.17541e-09
0.000472242 1.08778e-09
0.000473133 1.69325e-10
0.000478812 2.25749e-11
EOD
$d1 << EOD
0.000675325 0.00252364
0.000658519 0.00123205
0.000890244 0.000609355
0.001383 0.000303181
0.00244634 0.000151231
0.00440369 7.56063e-05
EOD
$d2 << EOD
0.000643547 8.59263e-07
0.000775864 2.15147e-07
0.00123412 5.38298e-08
0.00186031 1.34629e-08
0.00328222 3.36639e-09
0.00601621 8.41584e-10
EOD
$d3 << EOD
0.000487044 9.76131e-08
0.000484901 7.3024e-09
0.000528195 4.5635e-10
0.000698168 2.84614e-11
0.000904064 1.72726e-12
0.00135723 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
