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
0.0564897 0.000363388
0.0569466 5.9558e-06
0.0561187 1.22352e-06
0.0442031 1.69146e-06
0.0706503 1.52377e-06
0.112389 1.48835e-06
0.17772 1.47488e-06
EOD
$d1 << EOD
0.0152346 2.27988e-06
0.0298591 2.16165e-06
0.0596076 2.77333e-06
EOD
$d2 << EOD
0.00862147 0.692983
0.0162875 0.0909551
0.0266065 0.043833
0.0513874 0.00967797
0.103473 0.000273717
0.189016 7.94931e-05
0.337638 1.0866e-05
0.606648 6.168e-07
EOD
$d3 << EOD
0.00604205 0.925574
0.0202606 0.0677208
0.0732099 0.000267993
0.18947 7.74733e-05
0.372005 4.05086e-06
0.677687 1.20905e-06
1.14667 1.45113e-06
1.99892 1.47197e-06
EOD
$d4 << EOD
0.00825178 1.84316e-06
0.0131824 3.01372e-06
0.026412 2.54874e-06
0.0660215 1.24426e-06
EOD
$d5 << EOD
0.577273 0.000394679
0.586269 2.42804e-05
0.586343 7.26423e-06
0.572642 2.24147e-06
0.805934 1.90431e-06
EOD
$d6 << EOD
0.60373 0.000333447
0.587738 2.36895e-05
0.578909 3.2927e-06
0.566572 1.95073e-06
0.797158 1.92463e-06
EOD
$d7 << EOD
0.401088 7.33031e-05
0.396656 5.71697e-05
0.384403 2.73123e-06
0.388092 2.27064e-06
0.56163 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
