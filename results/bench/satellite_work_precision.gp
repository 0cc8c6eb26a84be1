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
0.053489 0.000363388
0.0531993 5.9558e-06
0.0506081 1.22352e-06
0.0423565 1.69146e-06
0.0684279 1.52377e-06
0.104319 1.48835e-06
0.169454 1.47488e-06
EOD
$d1 << EOD
0.0146025 2.27988e-06
0.0290245 2.16165e-06
0.0577896 2.77333e-06
EOD
$d2 << EOD
0.00829551 0.692983
0.0156658 0.0909551
0.0251502 0.043833
0.0490799 0.00967797
0.0987103 0.000273717
0.18499 7.94931e-05
0.335579 1.0866e-05
0.568659 6.168e-07
EOD
$d3 << EOD
0.00578936 0.925574
0.0192542 0.0677208
0.0691434 0.000267993
0.179378 7.74733e-05
0.346049 4.05086e-06
0.66123 1.20905e-06
1.10227 1.45113e-06
2.00318 1.47197e-06
EOD
$d4 << EOD
0.00919203 1.84316e-06
0.0148315 3.01372e-06
0.0278146 2.54874e-06
0.0706731 1.24426e-06
EOD
$d5 << EOD
0.548541 0.000394679
0.54521 2.42804e-05
0.524651 7.26423e-06
0.5101 2.24147e-06
0.760255 1.90431e-06
EOD
$d6 << EOD
0.568612 0.000333447
0.539126 2.36895e-05
0.5374 3.2927e-06
0.508796 1.95073e-06
0.76114 1.92463e-06
EOD
$d7 << EOD
0.38074 7.33031e-05
0.379643 5.71697e-05
0.358854 2.73123e-06
0.353116 2.27064e-06
0.54232 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
