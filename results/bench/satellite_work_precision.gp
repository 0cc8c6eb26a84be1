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
0.0769251 0.000363388
0.0770387 5.9558e-06
0.0768957 1.22352e-06
0.0602876 1.69146e-06
0.0964895 1.52377e-06
0.15292 1.48835e-06
0.238892 1.47488e-06
EOD
$d1 << EOD
0.0214126 2.27988e-06
0.0426106 2.16165e-06
0.0851947 2.77333e-06
EOD
$d2 << EOD
0.0115204 0.692983
0.0223728 0.0909551
0.0368998 0.0438276
0.0724114 0.00972929
0.141773 0.000273717
0.262279 7.94931e-05
0.467159 1.08687e-05
0.81362 6.18218e-07
EOD
$d3 << EOD
0.00821168 0.925574
0.0277048 0.0677208
0.102317 0.000267993
0.261141 7.74733e-05
0.523199 4.05086e-06
0.954112 1.20905e-06
1.60123 1.45113e-06
2.7555 1.47197e-06
EOD
$d4 << EOD
0.0117923 1.84316e-06
0.0193639 3.01372e-06
0.0425922 2.54874e-06
0.0910454 1.24426e-06
EOD
$d5 << EOD
0.467645 0.000394679
0.463195 2.42804e-05
0.457675 7.26423e-06
0.449739 2.24147e-06
0.637916 1.90431e-06
EOD
$d6 << EOD
0.480363 0.000333447
0.457912 2.36895e-05
0.459165 3.2927e-06
0.448084 1.95073e-06
0.646958 1.92463e-06
EOD
$d7 << EOD
0.3189 7.33031e-05
0.312832 5.71697e-05
0.304308 2.73123e-06
0.309786 2.27064e-06
0.451135 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
