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
0.0493193 0.000363388
0.0501953 5.9558e-06
0.0496961 1.22352e-06
0.0399223 1.69146e-06
0.0648545 1.52377e-06
0.102659 1.48835e-06
0.158685 1.47488e-06
EOD
$d1 << EOD
0.0184961 2.27988e-06
0.0369102 2.16165e-06
0.0721733 2.77333e-06
EOD
$d2 << EOD
0.00915568 0.692983
0.0176934 0.0909551
0.0291135 0.0438276
0.0572421 0.00972929
0.113364 0.000273717
0.209513 7.94931e-05
0.380558 1.08687e-05
0.650586 6.18218e-07
EOD
$d3 << EOD
0.00670519 0.925574
0.0219365 0.0677208
0.0788135 0.000267993
0.202571 7.74733e-05
0.416513 4.05086e-06
0.757581 1.20905e-06
1.27702 1.45113e-06
2.30374 1.47197e-06
EOD
$d4 << EOD
0.00849357 1.84316e-06
0.013537 3.01372e-06
0.0267584 2.54874e-06
0.06849 1.24426e-06
EOD
$d5 << EOD
0.308578 0.000394679
0.305358 2.42804e-05
0.299562 7.26423e-06
0.290035 2.24147e-06
0.417976 1.90431e-06
EOD
$d6 << EOD
0.315292 0.000333447
0.297172 2.36895e-05
0.300988 3.2927e-06
0.30298 1.95073e-06
0.430669 1.92463e-06
EOD
$d7 << EOD
0.213929 7.33031e-05
0.208907 5.71697e-05
0.204044 2.73123e-06
0.205938 2.27064e-06
0.299848 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
