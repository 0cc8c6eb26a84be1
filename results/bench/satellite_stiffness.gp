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
10000 0.0187023
100000 0.0778076
1e+06 0.269417
1e+07 0.889813
1e+08 2.79152
EOD
$d1 << EOD
10000 0.00321131
100000 0.0106183
1e+06 0.0362754
1e+07 0.117955
1e+08 0.371195
EOD
$d2 << EOD
10000 0.00587216
10000 0.0114444
10000 0.0227027
10000 0.0246009
10000 0.029123
10000 0.033091
10000 0.0359638
100000 0.00389882
100000 0.00460067
100000 0.00832073
100000 0.0215444
100000 0.060247
100000 0.0708342
100000 0.0826496
1e+06 0.00371101
1e+06 0.0037987
1e+06 0.00432741
1e+06 0.00699578
1e+06 0.0146865
1e+06 0.0405449
1e+06 0.101113
1e+07 0.00546812
1e+07 0.00652047
1e+07 0.00473086
1e+07 0.00572371
1e+07 0.00677854
1e+07 0.0117424
1e+07 0.0244325
1e+08 0.0102253
1e+08 0.0093283
1e+08 0.0108944
1e+08 0.00655766
1e+08 0.00692956
1e+08 0.00829151
1e+08 0.0111878
EOD
$d3 << EOD
10000 0.0136097
100000 0.0214258
1e+06 0.0336036
1e+07 0.0550243
1e+08 0.105969
EOD
$d4 << EOD
10000 0.0265436
100000 0.0596864
1e+06 0.123618
1e+07 0.260684
1e+08 0.47159
EOD
$d5 << EOD
10000 0.000890208
100000 0.00286274
1e+06 0.00936921
1e+07 0.0293036
1e+08 0.0857589
EOD
plot $d0 using 1:2 with linespoints title 'CVODE BDF (dense_analytic)' noenhanced, $d1 using 1:2 with linespoints title 'dopri5 (state norm)' noenhanced, $d2 using 1:2 with linespoints title 'radau5 (state norm)' noenhanced, $d3 using 1:2 with linespoints title 'rodas4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'rodas4 (state norm)' noenhanced, $d5 using 1:2 with linespoints title 'verlet (state norm)' noenhanced
