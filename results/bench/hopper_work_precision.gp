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
0.000363472 3.17542e-09
0.000358645 3.17545e-09
0.000364243 3.1754e-09
0.000377444 3.17546e-09
0.000365946 3.17541e-09
0.000374369 1.08778e-09
0.000378054 1.69325e-10
0.000396792 2.25749e-11
EOD
$d1 << EOD
0.000819643 0.00252364
0.00053657 0.00123205
0.000778892 0.000609355
0.00118144 0.000303181
0.00185268 0.000151231
0.00332637 7.56063e-05
EOD
$d2 << EOD
0.000470232 8.59263e-07
0.00059597 2.15147e-07
0.000860874 5.38298e-08
0.00139031 1.34629e-08
0.00241654 3.36639e-09
0.00443579 8.41584e-10
EOD
$d3 << EOD
0.000352816 9.76131e-08
0.000374979 7.3024e-09
0.00042193 4.5635e-10
0.000505814 2.84614e-11
0.000679664 1.72726e-12
0.0010603 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
