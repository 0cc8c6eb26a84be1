set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'energy.svg'
set title 'Energy by class'; set xlabel 'time [s]'; set ylabel 'energy [J]'
plot 'energy.csv' u 1:2 w l t 'kinetic', '' u 1:3 w l t 'gravitational', '' u 1:4 w l t 'internal springs', '' u 1:5 w l t 'leg springs', '' u 1:6 w l t 'contact', '' u 1:7 w l t 'dissipated', '' u 1:8 w l t 'actuator work', '' u 1:9 w l lw 2 t 'balance'
