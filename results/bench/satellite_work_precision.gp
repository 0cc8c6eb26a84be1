set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'satellite_work_precision.svg'
set title 'Satellite (k = 1e6 N/m, 20 s): omega error vs CPU time'
set xlabel 'CPU time [s]'
set ylabel 'relative omega error at 20 s'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.0530847 0.000363388
0.053306 5.9558e-06
0.0528766 1.22352e-06
0.0490746 1.69146e-06
0.0675259 1.52377e-06
0.108122 1.48835e-06
0.167461 1.47488e-06
EOD
$d1 << EOD
0.0139518 2.27988e-06
0.027923 2.16165e-06
0.0558578 2.77333e-06
EOD
$d2 << EOD
0.00881008 0.692983
0.0157909 0.0909551
0.0263795 0.043833
0.0500412 0.00967797
0.118567 0.000273717
0.183773 7.94931e-05
0.330387 1.0866e-05
0.574585 6.168e-07
EOD
$d3 << EOD
0.00579259 0.925574
0.0206508 0.0677208
0.0707442 0.000267993
0.192146 7.74733e-05
0.418302 4.05086e-06
0.663515 1.20905e-06
1.13934 1.45113e-06
1.94454 1.47197e-06
EOD
$d4 << EOD
0.00778812 1.84316e-06
0.0124106 3.01372e-06
0.0247774 2.54874e-06
0.0888673 1.24426e-06
EOD
$d5 << EOD
0.581447 0.000394679
0.571565 2.42804e-05
0.566274 7.26423e-06
0.557495 2.24147e-06
0.792482 1.90431e-06
EOD
$d6 << EOD
0.589883 0.000333447
0.567883 2.36895e-05
0.563595 3.2927e-06
0.548268 1.95073e-06
0.797075 1.92463e-06
EOD
$d7 << EOD
0.398148 7.33031e-05
0.38897 5.71697e-05
0.388097 2.73123e-06
0.387436 2.27064e-06
0.55813 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
