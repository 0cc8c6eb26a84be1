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
10000 0.0199374
100000 0.0808808
1e+06 0.266477
1e+07 0.892573
1e+08 2.88189
EOD
$d1 << EOD
10000 0.00375027
100000 0.0127378
1e+06 0.0429791
1e+07 0.141337
1e+08 0.447043
EOD
$d2 << EOD
10000 0.00596736
10000 0.0117502
10000 0.0231061
10000 0.0250654
10000 0.0307574
10000 0.0333845
10000 0.0375463
100000 0.00397498
100000 0.00463378
100000 0.0084729
100000 0.0220021
100000 0.0607552
100000 0.0728717
100000 0.0839272
1e+06 0.00379011
1e+06 0.00389267
1e+06 0.00441092
1e+06 0.00710142
1e+06 0.015068
1e+06 0.0411236
1e+06 0.101371
1e+07 0.0055582
1e+07 0.0066108
1e+07 0.00475197
1e+07 0.00568098
1e+07 0.00660249
1e+07 0.0115847
1e+07 0.0242161
1e+08 0.0101428
1e+08 0.00923402
1e+08 0.0107685
1e+08 0.00661603
1e+08 0.00698558
1e+08 0.00833207
1e+08 0.011194
EOD
$d3 << EOD
10000 0.0139257
100000 0.0224795
1e+06 0.0344232
1e+07 0.0543805
1e+08 0.107203
EOD
$d4 << EOD
10000 0.0272838
100000 0.0633118
1e+06 0.1256
1e+07 0.26646
1e+08 0.488841
EOD
$d5 << EOD
10000 0.00115651
100000 0.00359567
1e+06 0.0115456
1e+07 0.0356865
1e+08 0.115371
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
