set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'hop_forces.svg'
set multiplot layout 2,1
set title 'Hop height (CoM)'; set xlabel 'time [s]'; set ylabel 'z [m]'
plot 'trajectory.csv' u 1:4 w l t 'CoM z'
set title 'Leg actuator forces (+ pushes the body up)'; set ylabel 'force [N]'
plot 'feet.csv' u 1:2 w l t 'leg 0', 'feet.csv' u 1:3 w l t 'leg 1', 'feet.csv' u 1:4 w l t 'leg 2', 'feet.csv' u 1:5 w l t 'leg 3', 'feet.csv' u 1:6 w l dt 2 t 'ground on foot 0', 'feet.csv' u 1:7 w l dt 2 t 'ground on foot 1', 'feet.csv' u 1:8 w l dt 2 t 'ground on foot 2', 'feet.csv' u 1:9 w l dt 2 t 'ground on foot 3'
unset multiplot
