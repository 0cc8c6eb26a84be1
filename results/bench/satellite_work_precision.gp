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
0.199831 5.71669e-05
0.193456 2.73105e-06
0.195611 2.27064e-06
EOD
$d1 << EOD
0.0371784 0.000363388
0.0373729 5.9558e-06
0.0371908 1.22352e-06
0.0296728 1.69146e-06
0.0465601 1.52377e-06
0.0745441 1.48835e-06
0.116862 1.47488e-06
EOD
$d2 << EOD
0.003787 0.000209347
0.00434977 5.57521e-06
0.0147756 5.79792e-06
0.100669 2.27537e-06
EOD
$d3 << EOD
0.00961542 2.27988e-06
0.0191928 2.16165e-06
0.0380549 2.77333e-06
EOD
$d4 << EOD
0.00555556 0.692983
0.0106247 0.0909551
0.0174128 0.043833
0.0334729 0.00967797
0.0665759 0.000273717
0.122815 7.94931e-05
0.220082 1.0866e-05
0.384552 6.168e-07
EOD
$d5 << EOD
0.00392888 0.925574
0.013107 0.0677208
0.0483755 0.000267993
0.122083 7.74733e-05
0.241952 4.05086e-06
0.447362 1.20905e-06
0.757145 1.45113e-06
1.31947 1.47197e-06
EOD
$d6 << EOD
0.00551213 1.84316e-06
0.00880316 3.01372e-06
0.0175001 2.54874e-06
0.0439737 1.24426e-06
EOD
$d7 << EOD
0.276234 0.000394679
0.276693 2.42804e-05
0.266219 7.26423e-06
0.26753 2.24147e-06
0.37491 1.90431e-06
EOD
$d8 << EOD
0.285775 0.000333447
0.268156 2.36895e-05
0.267292 3.2927e-06
0.263751 1.95073e-06
0.375508 1.92463e-06
EOD
$d9 << EOD
0.182263 7.33031e-05
0.17969 5.71697e-05
0.174923 2.73123e-06
0.179652 2.27064e-06
0.265942 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'cvode_bdf (klu norm)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d5 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d6 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d8 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d9 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
