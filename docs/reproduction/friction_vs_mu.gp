set terminal pngcairo size 900,600
set output 'friction_vs_mu.png'
set title 'Macroscopic friction vs contact friction (2D biaxial, N = 500, p = 500 N/m)'
set xlabel 'microscopic friction μ'
set ylabel 'sin φ = (σ_1 − σ_3)/(σ_1 + σ_3)'
set key bottom right
set grid
set xrange [0:1.05]
set yrange [0:0.6]
set datafile missing 'NaN'
plot 'friction_vs_mu.dat' u 1:2 w lp pt 6 ps 1.5 t 'peak, dense (frictionless preparation)', \
     '' u 1:4 w lp pt 4 ps 1.5 t 'peak, loose (prepared with μ)', \
     '' u 1:3 w lp pt 7 ps 1.5 t 'end of test, dense', \
     '' u 1:5 w lp pt 5 ps 1.5 t 'end of test, loose'
