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
0.294547 0.000363388
0.297904 5.9558e-06
0.295921 1.22352e-06
0.246522 1.69146e-06
0.395568 1.52377e-06
0.652469 1.48835e-06
1.0085 1.47488e-06
EOD
$d1 << EOD
0.11103 2.27988e-06
0.221258 2.16165e-06
0.453604 2.77333e-06
EOD
$d2 << EOD
0.0160215 0.692983
0.0308254 0.0909551
0.0502922 0.0438276
0.102886 0.00972929
0.202612 0.000273717
0.368191 7.94931e-05
0.669107 1.08687e-05
1.1767 6.18218e-07
EOD
$d3 << EOD
0.0115491 0.925574
0.0384036 0.0677208
0.14039 0.000267993
0.36392 7.74733e-05
0.748557 4.05086e-06
1.33123 1.20905e-06
2.38174 1.45113e-06
3.94577 1.47197e-06
EOD
$d4 << EOD
0.347638 0.000394679
0.351602 2.42804e-05
0.363658 7.26423e-06
0.342588 2.24147e-06
0.488027 1.90431e-06
EOD
$d5 << EOD
0.37527 0.000333447
0.356838 2.36895e-05
0.369592 3.2927e-06
0.355106 1.95073e-06
0.514372 1.92463e-06
EOD
$d6 << EOD
0.258378 7.33031e-05
0.259907 5.71697e-05
0.251851 2.73123e-06
0.256557 2.27064e-06
0.374774 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
