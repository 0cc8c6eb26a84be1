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
0.202897 5.71669e-05
0.20022 2.73105e-06
0.203946 2.27064e-06
EOD
$d1 << EOD
0.0524718 0.000363388
0.0452823 5.9558e-06
0.0458257 1.22352e-06
0.0366481 1.69146e-06
0.0561159 1.52377e-06
0.0889 1.48835e-06
0.135038 1.47488e-06
EOD
$d2 << EOD
0.0036317 0.000209347
0.00420582 5.57521e-06
0.0147634 5.79792e-06
0.10215 2.27537e-06
EOD
$d3 << EOD
0.0112264 2.27988e-06
0.0225058 2.16165e-06
0.0448386 2.77333e-06
EOD
$d4 << EOD
0.00623737 0.692983
0.0118514 0.0909551
0.0202184 0.043833
0.03561 0.00967797
0.0758834 0.000273717
0.131264 7.94931e-05
0.233869 1.0866e-05
0.400016 6.168e-07
EOD
$d5 << EOD
0.0041356 0.925574
0.0145385 0.0677208
0.0530178 0.000267993
0.139237 7.74733e-05
0.270674 4.05086e-06
0.520599 1.20905e-06
0.800271 1.45113e-06
1.3816 1.47197e-06
EOD
$d6 << EOD
0.00670705 1.84316e-06
0.0107435 3.01372e-06
0.0215238 2.54874e-06
0.0571739 1.24426e-06
EOD
$d7 << EOD
0.281404 0.000394679
0.278688 2.42804e-05
0.276192 7.26423e-06
0.271196 2.24147e-06
0.382008 1.90431e-06
EOD
$d8 << EOD
0.288455 0.000333447
0.274255 2.36895e-05
0.275047 3.2927e-06
0.261925 1.95073e-06
0.385221 1.92463e-06
EOD
$d9 << EOD
0.18739 7.33031e-05
0.184896 5.71697e-05
0.181232 2.73123e-06
0.18191 2.27064e-06
0.26574 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'cvode_bdf (klu norm)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d5 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d6 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d8 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d9 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
