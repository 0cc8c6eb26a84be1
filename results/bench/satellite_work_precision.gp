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
0.298841 5.71669e-05
0.274568 2.73105e-06
0.281982 2.27064e-06
EOD
$d1 << EOD
0.0415187 0.000363388
0.041824 5.9558e-06
0.0416048 1.22352e-06
0.0329272 1.69146e-06
0.0524128 1.52377e-06
0.0831623 1.48835e-06
0.13462 1.47488e-06
EOD
$d2 << EOD
0.00466188 0.000209347
0.00539676 5.57521e-06
0.0177216 5.79792e-06
0.118071 2.27537e-06
EOD
$d3 << EOD
0.0106922 2.27988e-06
0.0213172 2.16165e-06
0.0426878 2.77333e-06
EOD
$d4 << EOD
0.00618759 0.692983
0.0115197 0.0909551
0.0189098 0.043833
0.0362925 0.00967797
0.0735965 0.000273717
0.134554 7.94931e-05
0.238067 1.0866e-05
0.438807 6.168e-07
EOD
$d5 << EOD
0.00423593 0.925574
0.0141225 0.0677208
0.0518756 0.000267993
0.131031 7.74733e-05
0.260898 4.05086e-06
0.492765 1.20905e-06
0.825471 1.45113e-06
1.44381 1.47197e-06
EOD
$d6 << EOD
0.00805575 1.84316e-06
0.0116724 3.01372e-06
0.0250009 2.54874e-06
0.0579873 1.24426e-06
EOD
$d7 << EOD
0.471551 0.000394679
0.431792 2.42804e-05
0.425819 7.26423e-06
0.417189 2.24147e-06
0.591719 1.90431e-06
EOD
$d8 << EOD
0.445925 0.000333447
0.447467 2.36895e-05
0.421808 3.2927e-06
0.412328 1.95073e-06
0.610227 1.92463e-06
EOD
$d9 << EOD
0.280911 7.33031e-05
0.27932 5.71697e-05
0.26262 2.73123e-06
0.268517 2.27064e-06
0.406461 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'cvode_bdf (klu norm)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d5 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d6 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d8 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d9 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
