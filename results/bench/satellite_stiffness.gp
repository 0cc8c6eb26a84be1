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
10000 0.0404321
100000 0.164441
1e+06 0.572197
1e+07 1.90084
1e+08 6.06945
EOD
$d1 << EOD
10000 0.00631697
100000 0.0201372
1e+06 0.0708642
1e+07 0.245335
1e+08 0.707889
EOD
$d2 << EOD
10000 0.0608389
100000 0.129581
1e+06 0.184913
1e+07 0.129097
1e+08 0.195112
EOD
$d3 << EOD
10000 0.0234675
100000 0.0344723
1e+06 0.0551033
1e+07 0.0898942
1e+08 0.173981
EOD
$d4 << EOD
10000 0.0434541
100000 0.0987798
1e+06 0.199858
1e+07 0.419747
1e+08 0.890353
EOD
$d5 << EOD
10000 0.00179179
100000 0.00486696
1e+06 0.0155566
1e+07 0.0513718
1e+08 0.150745
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
