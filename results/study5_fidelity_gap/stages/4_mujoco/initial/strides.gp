set terminal svg size 900,640 dynamic enhanced font 'Helvetica,11'
set datafile separator ','
set key autotitle columnhead
set grid
set output 'strides.svg'
set multiplot layout 2,1
set title 'Apex height per stride'; set xlabel 'stride'; set ylabel 'apex height [m]'
plot 'strides.csv' u 1:($14>0?$14:1/0) w lp t 'apex'
set title 'Duty cycle per stride'; set ylabel 'stance / stride time'
plot 'strides.csv' u 1:($16>0?$17:1/0) w lp t 'duty cycle'
unset multiplot
