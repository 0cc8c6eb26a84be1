set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'path3d.svg'
set title 'Path of the CoM'; set xlabel 'x [m]'; set ylabel 'y [m]'
stats 'trajectory.csv' u 4 nooutput name 'PZ'
pz_top = PZ_max > 0 ? PZ_max : 1
pz_step = 10**floor(log10(pz_top / 3.0)); pz_r = pz_top / pz_step
pz_step = pz_step * (pz_r <= 3 ? 1 : pz_r <= 6 ? 2 : pz_r <= 15 ? 5 : 10)
set zrange [0:*]; set ztics 0, pz_step; set xyplane at 0
set zlabel 'z [m]' rotate parallel
set view 60,30,1,1.3
splot 'trajectory.csv' u 2:3:4 w l t 'CoM', '' u 14:15:(0) w l dt 2 t 'setpoint'
