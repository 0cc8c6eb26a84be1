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
0.000392015 3.17542e-09
0.000389802 3.17545e-09
0.000383242 3.1754e-09
0.000390032 3.17546e-09
0.00038858 3.17541e-09
0.000384214 1.08778e-09
0.000432426 1.69325e-10
0.000399025 2.25749e-11
EOD
$d1 << EOD
0.000595069 0.00252364
0.000557242 0.00123205
0.000758533 0.000609355
0.00118467 0.000303181
0.00196807 0.000151231
0.00352415 7.56063e-05
EOD
$d2 << EOD
0.000511453 8.59263e-07
0.000635569 2.15147e-07
0.000914005 5.38298e-08
0.00144908 1.34629e-08
0.00259024 3.36639e-09
0.0046109 8.41584e-10
EOD
$d3 << EOD
0.000387899 9.76131e-08
0.000404413 7.3024e-09
0.000439036 4.5635e-10
0.000568358 2.84614e-11
0.000757301 1.72726e-12
0.00110381 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
