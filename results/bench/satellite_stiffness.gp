set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'satellite_stiffness.svg'
set title 'Satellite, tol 1e-6: CPU time vs internal stiffness'
set xlabel 'internal stiffness [N/m]'
set ylabel 'CPU time [s]'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
10000 0.0324129
100000 0.133469
1e+06 0.462943
1e+07 1.52669
1e+08 4.80648
EOD
$d1 << EOD
10000 0.00670451
100000 0.0224109
1e+06 0.0774129
1e+07 0.249593
1e+08 0.803626
EOD
$d2 << EOD
10000 0.111488
100000 0.258459
1e+06 0.370095
1e+07 0.261775
1e+08 0.422584
EOD
$d3 << EOD
10000 0.0288964
100000 0.045356
1e+06 0.0729082
1e+07 0.116479
1e+08 0.222557
EOD
$d4 << EOD
10000 0.0577119
100000 0.129309
1e+06 0.256864
1e+07 0.545591
1e+08 0.996603
EOD
$d5 << EOD
10000 0.00183894
100000 0.005723
1e+06 0.0179873
1e+07 0.0568807
1e+08 0.183234
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
