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
0.0659549 0.000363388
0.0660249 5.9558e-06
0.0659462 1.22352e-06
0.0518594 1.69146e-06
0.0819924 1.52377e-06
0.131602 1.48835e-06
0.207866 1.47488e-06
EOD
$d1 << EOD
0.0187191 2.27988e-06
0.0376018 2.16165e-06
0.0773315 2.77333e-06
EOD
$d2 << EOD
0.0130442 0.692983
0.0251863 0.0909551
0.0419948 0.0438276
0.0812876 0.00972929
0.15833 0.000273717
0.293856 7.94931e-05
0.528092 1.08687e-05
0.929591 6.18218e-07
EOD
$d3 << EOD
0.00926973 0.925574
0.0313237 0.0677208
0.116187 0.000267993
0.289395 7.74733e-05
0.581428 4.05086e-06
1.05749 1.20905e-06
1.79717 1.45113e-06
3.24509 1.47197e-06
EOD
$d4 << EOD
0.0090981 1.84316e-06
0.0149619 3.01372e-06
0.0297903 2.54874e-06
0.0743002 1.24426e-06
EOD
$d5 << EOD
0.599502 0.000394679
0.578531 2.42804e-05
0.596019 7.26423e-06
0.562899 2.24147e-06
0.814215 1.90431e-06
EOD
$d6 << EOD
0.611137 0.000333447
0.589335 2.36895e-05
0.565601 3.2927e-06
0.70203 1.95073e-06
0.835774 1.92463e-06
EOD
$d7 << EOD
0.423376 7.33031e-05
0.394922 5.71697e-05
0.382606 2.73123e-06
0.386992 2.27064e-06
0.600058 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
