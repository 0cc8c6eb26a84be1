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
0.199839 5.71669e-05
0.193241 2.73105e-06
0.202282 2.27064e-06
EOD
$d1 << EOD
0.0361491 0.000363388
0.0366537 5.9558e-06
0.0354733 1.22352e-06
0.0279877 1.69146e-06
0.0455621 1.52377e-06
0.0708405 1.48835e-06
0.114391 1.47488e-06
EOD
$d2 << EOD
0.00372829 0.000209347
0.00425232 5.57521e-06
0.0145538 5.79792e-06
0.0990185 2.27537e-06
EOD
$d3 << EOD
0.00948829 2.27988e-06
0.0189846 2.16165e-06
0.0376434 2.77333e-06
EOD
$d4 << EOD
0.00535443 0.692983
0.0101728 0.0909551
0.0171744 0.043833
0.0319506 0.00967797
0.0648188 0.000273717
0.122945 7.94931e-05
0.217944 1.0866e-05
0.380132 6.168e-07
EOD
$d5 << EOD
0.00376826 0.925574
0.0126071 0.0677208
0.0483166 0.000267993
0.118413 7.74733e-05
0.23996 4.05086e-06
0.447058 1.20905e-06
0.747099 1.45113e-06
1.32934 1.47197e-06
EOD
$d6 << EOD
0.00597637 1.84316e-06
0.00959984 3.01372e-06
0.0191167 2.54874e-06
0.0476988 1.24426e-06
EOD
$d7 << EOD
0.292989 0.000394679
0.287492 2.42804e-05
0.280403 7.26423e-06
0.269708 2.24147e-06
0.385195 1.90431e-06
EOD
$d8 << EOD
0.294041 0.000333447
0.283858 2.36895e-05
0.273961 3.2927e-06
0.268305 1.95073e-06
0.399617 1.92463e-06
EOD
$d9 << EOD
0.185907 7.33031e-05
0.191083 5.71697e-05
0.181155 2.73123e-06
0.180756 2.27064e-06
0.278654 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'cvode_bdf (klu norm)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d5 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d6 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d8 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d9 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
