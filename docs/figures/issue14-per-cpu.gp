# Issue 14's targets per CPU: the latest row of each CPU's table in
# docs/performance.md. From docs/figures: gnuplot issue14-per-cpu.gp
set terminal pngcairo size 1100,900 font ',10'
set output 'issue14-per-cpu.png'
set datafile separator whitespace
set style data histograms
set style histogram errorbars gap 2 lw 1
set style fill solid 0.6 border -1
set boxwidth 0.9
set grid ytics
set key outside right top
set lmargin at screen 0.08
set rmargin at screen 0.76
set multiplot layout 3,1 title "dembox on the CPUs measured (session of the figures in brackets; bars: median of the rounds, whiskers: range)"
set ylabel 'dembox / LAMMPS per core'
set yrange [0:4.6]
set arrow 1 from graph 0, first 2 to graph 1, first 2 nohead dt 2 lw 2 lc rgb 'red' front
set label 1 'issue 14: at least 2' at screen 0.78, first 2 tc rgb 'red'
plot 'issue14-per-cpu.dat' u 2:3:4:xtic(1) t 'N = 3375', \
     '' u 5:6:7 t 'N = 20000', \
     '' u 8:9:10 t 'N = 216000'
set ylabel 'two threads / one, N = 20000'
set yrange [0:2.6]
set arrow 1 from graph 0, first 1.85 to graph 1, first 1.85 nohead dt 2 lw 2 lc rgb 'red' front
set label 1 'issue 14: at least 1.85' at screen 0.78, first 1.85 tc rgb 'red'
plot 'issue14-per-cpu.dat' u 11:12:13:xtic(1) t 'dembox bench by turns'
set ylabel 'cost per particle-step, 216000 / 3375'
set yrange [0:2.4]
set arrow 1 from graph 0, first 1.2 to graph 1, first 1.2 nohead dt 2 lw 2 lc rgb 'red' front
set label 1 'issue 14: at most 1.2' at screen 0.78, first 1.2 tc rgb 'red'
plot 'issue14-per-cpu.dat' u 14:15:16:xtic(1) t 'dembox between walls', \
     '' u 20:21:22 t 'dembox, periodic cell', \
     '' u 17:18:19 t 'LAMMPS, periodic box'
unset multiplot
