set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'leg_force.svg'
set title 'Net leg force (world)'; set xlabel 'time [s]'; set ylabel 'force [N]'
plot 'trajectory.csv' u 1:17 w l t 'F_x', '' u 1:18 w l t 'F_y', '' u 1:19 w l t 'F_z'
