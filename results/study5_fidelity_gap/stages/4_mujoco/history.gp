set terminal svg size 900,500 dynamic enhanced font 'Helvetica,11'
set output 'history.svg'
set datafile separator ','
set grid
set title 'Optimization history'
set xlabel 'evaluation'
set ylabel 'cost'
plot 'history.csv' every ::1 u 1:($3==1 ? $4 : 1/0) w p pt 7 ps 0.4 t 'cost', '' every ::1 u 1:(strlen(strcol(6))>0 ? $6 : 1/0) w l lw 2 t 'best feasible'
