# bench/trials_log.py trials-whole.txt --window 2
set terminal pngcairo size 1000,700 font ',10'
set output 'trials-cyclic3d-paper-zen4.png'
set multiplot layout 2,1
set key outside right
set grid
set ylabel 'median time in the trials (us per pass)'
set yrange [0:*]
plot 'trials-cyclic3d-paper-zen4.dat' u 1:3 w lp pt 7 ps 0.4 t 'gathers', \
     'trials-cyclic3d-paper-zen4.dat' u 1:4 w lp pt 7 ps 0.4 t 'loads', \
     'trials-cyclic3d-paper-zen4.dat' u 1:5 w lp pt 7 ps 0.4 t 'records', \
     'trials-cyclic3d-paper-zen4.dat' u 1:6 w lp pt 7 ps 0.4 t 'blocks', \
     'trials-cyclic3d-paper-zen4.dat' u 1:7 w lp pt 7 ps 0.4 t 'ring'
set xlabel 'wall clock since the first trial (min), windows of 2 min'
set ylabel 'share of trials after which in use'
set yrange [0:1]
plot 'trials-cyclic3d-paper-zen4.dat' u 1:8 w steps t 'gathers', \
     'trials-cyclic3d-paper-zen4.dat' u 1:9 w steps t 'loads', \
     'trials-cyclic3d-paper-zen4.dat' u 1:10 w steps t 'records', \
     'trials-cyclic3d-paper-zen4.dat' u 1:11 w steps t 'blocks', \
     'trials-cyclic3d-paper-zen4.dat' u 1:12 w steps t 'ring'
unset multiplot
