set terminal svg size 900,560 dynamic enhanced font 'Helvetica,11'
set output 'fidelity_robustness.svg'
set title 'Fidelity ladder: fraction of 8 seeded disturbance trials stabilized (map_seed_duty, row 0)' noenhanced
set xlabel 'duty cycle [-]'
set ylabel 'stabilized fraction [-]'
set yrange [-0.05:1.05]
set offsets 0.05, 0.05, 0, 0
set grid
set key outside right
$d0 << EOD
0.1 1
0.2 1
0.3 1
0.4 1
EOD
$d1 << EOD
0.1 1
0.2 1
0.3 0.875
0.4 0
EOD
$d2 << EOD
0.1 1
0.2 1
0.3 0.875
0.4 0
EOD
$d3 << EOD
0.1 1
0.2 1
0.3 0.875
0.4 0
EOD
plot $d0 using 1:2 with linespoints lw 3 dt 1 pt 4 ps 1.5 title 'impulse (boundary all_good 0.4)' noenhanced, $d1 using 1:2 with linespoints lw 2 dt 2 pt 6 ps 1.5 title 'pulse (boundary bisected 0.2875)' noenhanced, $d2 using 1:2 with linespoints lw 1 dt 3 pt 8 ps 1.5 title 'rigid (boundary bisected 0.2875)' noenhanced, $d3 using 1:2 with linespoints lw 0 dt 4 pt 10 ps 1.5 title 'pseudo_rigid (boundary bisected 0.2875)' noenhanced
