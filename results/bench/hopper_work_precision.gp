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
0.00042963 3.17542e-09
0.000428355 3.17545e-09
0.000428289 3.1754e-09
0.000430122 3.17546e-09
0.000427062 3.17541e-09
0.000427113 1.08778e-09
0.00050093 1.69325e-10
0.000437909 2.25749e-11
EOD
$d1 << EOD
0.000632486 0.00252364
0.000723555 0.00123205
0.000959567 0.000609355
0.00145985 0.000303181
0.00244878 0.000151231
0.0044922 7.56063e-05
EOD
$d2 << EOD
0.000614938 8.59263e-07
0.000815044 2.15147e-07
0.00117361 5.38298e-08
0.00188548 1.34629e-08
0.00335009 3.36639e-09
0.00616832 8.41584e-10
EOD
$d3 << EOD
0.000468364 9.76131e-08
0.000507725 7.3024e-09
0.000552207 4.5635e-10
0.00068534 2.84614e-11
0.000930036 1.72726e-12
0.00148925 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
