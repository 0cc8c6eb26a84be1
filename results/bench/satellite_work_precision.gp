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
0.0671895 0.000363388
0.0690645 5.9558e-06
0.0710828 1.22352e-06
0.0930468 1.69146e-06
0.0827635 1.52377e-06
0.13381 1.48835e-06
0.218992 1.47488e-06
EOD
$d1 << EOD
0.0197565 2.27988e-06
0.0410551 2.16165e-06
0.0829811 2.77333e-06
EOD
$d2 << EOD
0.00902757 0.692983
0.0172053 0.0909551
0.0304056 0.043833
0.0544923 0.00967797
0.176266 0.000273717
0.277087 7.94931e-05
0.353135 1.0866e-05
0.643629 6.168e-07
EOD
$d3 << EOD
0.00629753 0.925574
0.0208161 0.0677208
0.0775846 0.000267993
0.204968 7.74733e-05
0.400476 4.05086e-06
0.994321 1.20905e-06
1.22152 1.45113e-06
2.12785 1.47197e-06
EOD
$d4 << EOD
0.0102846 1.84316e-06
0.018649 3.01372e-06
0.0327652 2.54874e-06
0.101778 1.24426e-06
EOD
$d5 << EOD
0.584859 0.000394679
0.585427 2.42804e-05
0.567565 7.26423e-06
0.557106 2.24147e-06
0.845404 1.90431e-06
EOD
$d6 << EOD
0.602398 0.000333447
0.563968 2.36895e-05
0.649017 3.2927e-06
0.58384 1.95073e-06
0.802501 1.92463e-06
EOD
$d7 << EOD
0.408329 7.33031e-05
0.396551 5.71697e-05
0.384304 2.73123e-06
0.385776 2.27064e-06
0.5633 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
