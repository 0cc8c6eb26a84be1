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
0.000292116 3.17542e-09
0.000290504 3.17545e-09
0.000317844 3.1754e-09
0.000292917 3.17546e-09
0.000291114 3.17541e-09
0.000290193 1.08778e-09
0.000326718 1.69325e-10
0.000297894 2.25749e-11
EOD
$d1 << EOD
0.000551743 0.00252364
0.000538483 0.00123205
0.000732533 0.000609355
0.00111922 0.000303181
0.0018723 0.000151231
0.00345158 7.56063e-05
EOD
$d2 << EOD
0.000478154 8.59263e-07
0.000604061 2.15147e-07
0.000903698 5.38298e-08
0.0014046 1.34629e-08
0.00240335 3.36639e-09
0.0044645 8.41584e-10
EOD
$d3 << EOD
0.000357083 9.76131e-08
0.000384113 7.3024e-09
0.000443112 4.5635e-10
0.00051644 2.84614e-11
0.000688187 1.72726e-12
0.00112749 6.37391e-14
EOD
plot $d0 using 1:2 with linespoints title 'dopri5' noenhanced, $d1 using 1:2 with linespoints title 'euler' noenhanced, $d2 using 1:2 with linespoints title 'rk2' noenhanced, $d3 using 1:2 with linespoints title 'rk4' noenhanced
