# Disagreement map of map_study3_full_tilt_offset (written by pronk map; restyle and run: gnuplot disagreement.gp)
set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set output 'disagreement.svg'
set title 'Disagreement pulse vs pseudo_rigid: fraction of 8 trials stabilized by exactly one model' noenhanced
set palette defined (0 '#ffffff', 0.25 '#fdd49e', 0.5 '#fc8d59', 1 '#b30000')
set cbrange [0:1]
set xlabel 'lateral_offset [m]' noenhanced
set ylabel 'tilt_deg [deg]' noenhanced
set xrange [-0.05:0.45000000000000007]
set yrange [-2.5:12.5]
set key outside bottom center horizontal
# x y x_lo x_hi y_lo y_hi value
$cells << EOD
0 0 -0.05 0.05 -2.5 2.5 0
0.1 0 0.05 0.15000000000000002 -2.5 2.5 0
0.2 0 0.15000000000000002 0.25 -2.5 2.5 0.25
0.3 0 0.25 0.35 -2.5 2.5 1
0.4 0 0.35 0.45000000000000007 -2.5 2.5 1
0 5 -0.05 0.05 2.5 7.5 0
0.1 5 0.05 0.15000000000000002 2.5 7.5 0
0.2 5 0.15000000000000002 0.25 2.5 7.5 0.75
0.3 5 0.25 0.35 2.5 7.5 1
0.4 5 0.35 0.45000000000000007 2.5 7.5 1
0 10 -0.05 0.05 7.5 12.5 0
0.1 10 0.05 0.15000000000000002 7.5 12.5 0
0.2 10 0.15000000000000002 0.25 7.5 12.5 1
0.3 10 0.25 0.35 7.5 12.5 1
0.4 10 0.35 0.45000000000000007 7.5 12.5 1
EOD
# boundary, row value, lowest cell with all trials stabilized (rows with one)
$boundary << EOD
0.15625000000000003 0 0
0.1125 5 0
0.125 10 0
EOD
plot $cells using 1:2:3:4:5:6:7 with boxxyerror fill solid 1.0 noborder lc palette notitle, \
     $boundary using 1:2 with linespoints lw 2 pt 7 ps 0.6 lc rgb 'black' title 'boundary: all pseudo_rigid trials stabilized' noenhanced
