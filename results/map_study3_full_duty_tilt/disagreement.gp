# Disagreement map of map_study3_full_duty_tilt (written by pronk map; restyle and run: gnuplot disagreement.gp)
set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'disagreement.svg'
set title 'Disagreement pulse vs pseudo_rigid: fraction of 8 trials stabilized by exactly one model' noenhanced
set palette defined (0 '#ffffff', 0.25 '#fdd49e', 0.5 '#fc8d59', 1 '#b30000')
set cbrange [0:1]
set xlabel 'duty_cycle' noenhanced
set ylabel 'tilt_deg [deg]' noenhanced
set xrange [0.07500000000000001:0.32499999999999996]
set yrange [-2.5:12.5]
set key outside bottom center horizontal
# x y x_lo x_hi y_lo y_hi value
$cells << EOD
0.1 0 0.07500000000000001 0.125 -2.5 2.5 1
0.15 0 0.125 0.175 -2.5 2.5 0
0.2 0 0.175 0.225 -2.5 2.5 0.5
0.25 0 0.225 0.275 -2.5 2.5 0
0.3 0 0.275 0.32499999999999996 -2.5 2.5 0
0.1 5 0.07500000000000001 0.125 2.5 7.5 1
0.15 5 0.125 0.175 2.5 7.5 0
0.2 5 0.175 0.225 2.5 7.5 0.625
0.25 5 0.225 0.275 2.5 7.5 0.125
0.3 5 0.275 0.32499999999999996 2.5 7.5 0
0.1 10 0.07500000000000001 0.125 7.5 12.5 1
0.15 10 0.125 0.175 7.5 12.5 0.125
0.2 10 0.175 0.225 7.5 12.5 1
0.25 10 0.225 0.275 7.5 12.5 0
0.3 10 0.275 0.32499999999999996 7.5 12.5 0
EOD
# boundary, row value, lowest cell with all trials stabilized (rows with one; a blank
# line at a row with none, where the line breaks)
$boundary << EOD
0.225 0 0.15
0.225 5 0.15
0.225 10 0.15
EOD
plot $cells using 1:2:3:4:5:6:7 with boxxyerror fill solid 1.0 noborder lc palette notitle, \
     $boundary using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb 'black' title 'boundary: all pseudo_rigid trials stabilized' noenhanced, \
     $boundary using 3:2 with linespoints lw 2 dt 2 pt 6 ps 0.6 lc rgb 'black' title 'lowest cell with all trials stabilized' noenhanced
