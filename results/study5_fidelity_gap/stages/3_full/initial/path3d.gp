set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'path3d.svg'
set title 'Path of the CoM'; set xlabel 'x [m]'; set ylabel 'y [m]'; set zlabel 'z [m]'
set view 60,30
splot 'trajectory.csv' u 2:3:4 w l t 'CoM', '' u 14:15:(0) w l dt 2 t 'setpoint'
