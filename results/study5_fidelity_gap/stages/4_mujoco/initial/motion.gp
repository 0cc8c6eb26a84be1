set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'motion.svg'
set multiplot layout 2,2 title 'pr_running (mujoco)' noenhanced
set title 'Body position'; set xlabel 'time [s]'; set ylabel 'position [m]'
plot 'trajectory.csv' u 1:2 w l t 'x', '' u 1:3 w l t 'y', '' u 1:4 w l t 'z', '' u 1:14 w l dt 2 t 'x_d'
set title 'Body horizontal velocity'; set ylabel 'velocity [m/s]'
plot 'trajectory.csv' u 1:5 w l t 'v_x', '' u 1:6 w l t 'v_y'
set title 'Body attitude (Euler 1-2-3)'; set ylabel 'angle [deg]'
plot 'trajectory.csv' u 1:8 w l t 'roll', '' u 1:9 w l t 'pitch', '' u 1:10 w l t 'yaw'
set title 'Trajectory of the CoM'; set xlabel 'x [m]'; set ylabel 'y [m]'
stats 'trajectory.csv' u 4 nooutput name 'PZ'
pz_top = PZ_max > 0 ? PZ_max : 1
pz_step = 10**floor(log10(pz_top / 3.0)); pz_r = pz_top / pz_step
pz_step = pz_step * (pz_r <= 3 ? 1 : pz_r <= 6 ? 2 : pz_r <= 15 ? 5 : 10)
set zrange [0:*]; set ztics 0, pz_step; set xyplane at 0
set zlabel 'z [m]' rotate parallel
set view 60,30,1,1.3
splot 'trajectory.csv' u 2:3:4 w l t 'CoM'
unset multiplot
