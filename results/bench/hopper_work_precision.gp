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
0.000395691 3.17542e-09
0.000386777 3.17545e-09
0.000449941 3.1754e-09
0.000409171 3.17546e-09
0.000390283 3.17541e-09
0.000386237 1.08778e-09
0.000392766 1.69325e-10
0.000458455 2.25749e-11
EOD
$d1 << EOD
0.000560346 0.00252364
0.000561939 0.00123205
0.000761778 0.000609355
0.00114473 0.000303181
0.00199177 0.000151231
0.00353325 7.56063e-05
EOD
$d2 << EOD
0.000513697 8.59263e-07
0.000637773 2.15147e-07
0.000916608 5.38298e-08
0.00151291 1.34629e-08
0.0026381 3.36639e-09
0.00484467 8.41584e-10
EOD
$d3 << EOD
0.000388951 9.76131e-08
0.000409762 7.3024e-09
0.000451935 4.5635e-10
0.000546997 2.84614e-11
0.000785853 1.72726e-12
0.00115449 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
