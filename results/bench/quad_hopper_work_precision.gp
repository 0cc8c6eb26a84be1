set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'quad_hopper_work_precision.svg'
set title 'Quad spring hopper drop (undamped): energy error vs cost'
set xlabel 'CPU time per simulated second [s/s]'
set ylabel 'energy error / drop energy'
set logscale xy
set format x '10^{%L}'
set format y '10^{%L}'
set grid
set key outside right
$d0 << EOD
0.00187206 0.104493
0.00361931 0.0463784
0.00754766 0.0412629
0.0174631 0.0426167
EOD
$d1 << EOD
0.00734732 0.0478461
0.0155393 0.04919
0.0305735 0.0448712
0.0594251 0.0430324
EOD
$d2 << EOD
0.00366543 0.104493
0.00727468 0.0463784
0.0144278 0.0412629
0.0288796 0.0426167
EOD
$d3 << EOD
0.823126 0.222796
1.17694 0.014682
1.68367 0.000879192
EOD
$d4 << EOD
0.592609 0.554945
0.952752 0.0341786
1.50727 0.0019411
EOD
plot $d0 using 1:2 with linespoints title 'MuJoCo Euler' noenhanced, $d1 using 1:2 with linespoints title 'MuJoCo RK4' noenhanced, $d2 using 1:2 with linespoints title 'MuJoCo implicit' noenhanced, $d3 using 1:2 with linespoints title 'pronk RODAS4 (body norm)' noenhanced, $d4 using 1:2 with linespoints title 'pronk RODAS4 (state norm)' noenhanced
