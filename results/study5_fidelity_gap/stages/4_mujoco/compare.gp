set terminal svg size 900,900 dynamic enhanced font 'Helvetica,11'
set output 'compare.svg'
set datafile separator ','
set grid
set multiplot layout 3,2 title 'study5_fidelity_gap_mujoco: initial vs tuned (first scenario)' noenhanced
set xlabel 'time [s]'
set title 'Lateral position y'; set ylabel 'y [m]'
plot 'initial/trajectory.csv' every ::1 u 1:3 w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:3 w l t 'tuned'
set title 'Roll'; set ylabel 'roll [deg]'
plot 'initial/trajectory.csv' every ::1 u 1:8 w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:8 w l t 'tuned'
set title 'Height'; set ylabel 'z [m]'
plot 'initial/trajectory.csv' every ::1 u 1:4 w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:4 w l t 'tuned'
set title 'x - x_d'; set ylabel 'error [m]'
plot 'initial/trajectory.csv' every ::1 u 1:($2-$14) w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:($2-$14) w l t 'tuned'
set title 'Pitch'; set ylabel 'pitch [deg]'
plot 'initial/trajectory.csv' every ::1 u 1:9 w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:9 w l t 'tuned'
set title 'Yaw'; set ylabel 'yaw [deg]'
plot 'initial/trajectory.csv' every ::1 u 1:10 w l t 'initial', 'tuned/trajectory.csv' every ::1 u 1:10 w l t 'tuned'
unset multiplot
