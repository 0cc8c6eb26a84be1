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
0.0564938 0.000363388
0.0567865 5.9558e-06
0.0559583 1.22352e-06
0.0444016 1.69146e-06
0.0714373 1.52377e-06
0.112909 1.48835e-06
0.17579 1.47488e-06
EOD
$d1 << EOD
0.0147095 2.27988e-06
0.0296184 2.16165e-06
0.0586956 2.77333e-06
EOD
$d2 << EOD
0.0087325 0.692983
0.0167136 0.0909551
0.0272809 0.043833
0.0525862 0.00967797
0.10543 0.000273717
0.192991 7.94931e-05
0.347277 1.0866e-05
0.604484 6.168e-07
EOD
$d3 << EOD
0.0066166 0.925574
0.0203536 0.0677208
0.0744732 0.000267993
0.190504 7.74733e-05
0.380393 4.05086e-06
0.704308 1.20905e-06
1.18993 1.45113e-06
2.07592 1.47197e-06
EOD
$d4 << EOD
0.00958985 1.84316e-06
0.0152848 3.01372e-06
0.030658 2.54874e-06
0.0765278 1.24426e-06
EOD
$d5 << EOD
0.561502 0.000394679
0.564189 2.42804e-05
0.56226 7.26423e-06
0.551205 2.24147e-06
0.776946 1.90431e-06
EOD
$d6 << EOD
0.576589 0.000333447
0.558104 2.36895e-05
0.55626 3.2927e-06
0.544288 1.95073e-06
0.774527 1.92463e-06
EOD
$d7 << EOD
0.388063 7.33031e-05
0.3867 5.71697e-05
0.374072 2.73123e-06
0.380332 2.27064e-06
0.546748 1.9502e-06
EOD
plot $d0 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d1 using 1:2 with linespoints title 'rk4 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d4 using 1:2 with linespoints title 'verlet (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d6 using 1:2 with linespoints title 'CVODE BDF (dense_dq)' noenhanced, $d7 using 1:2 with linespoints title 'CVODE BDF (sparse_klu_analytic)' noenhanced
