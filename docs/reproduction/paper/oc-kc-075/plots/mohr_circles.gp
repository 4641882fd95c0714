# mohr_circles.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot mohr_circles.gp
# The data are in mohr_circles.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "mohr_circles.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Mohr circles at peak and the flow function τ = c + σ tan φ"
set xlabel "normal stress σ"
set ylabel "shear stress τ"
set grid
set key below box
set clip two
set size ratio -1
set xrange [0:539.12513]
set yrange [0:323.475078]
plot \
  "mohr_circles.dat" index 0 with lines linewidth 2 linecolor 1 title "p = 100" noenhanced, \
  "mohr_circles.dat" index 1 with lines linewidth 2 linecolor 2 title "p = 250" noenhanced, \
  "mohr_circles.dat" index 2 with lines dashtype 2 linewidth 2 linecolor "black" title "flow function φ = 8.6°, c = 58, R² = 1.000 (seed=1)" noenhanced, \
  "mohr_circles.dat" index 3 with lines linewidth 2 linecolor 1 notitle, \
  "mohr_circles.dat" index 4 with lines linewidth 2 linecolor 2 notitle, \
  "mohr_circles.dat" index 5 with lines dashtype 3 linewidth 2 linecolor "black" title "flow function φ = 11.2°, c = 48.3, R² = 1.000 (seed=2)" noenhanced, \
  "mohr_circles.dat" index 6 with lines linewidth 2 linecolor 1 notitle, \
  "mohr_circles.dat" index 7 with lines linewidth 2 linecolor 2 notitle, \
  "mohr_circles.dat" index 8 with lines dashtype 4 linewidth 2 linecolor "black" title "flow function φ = 9.0°, c = 52.4, R² = 1.000 (seed=3)" noenhanced, \
  0 linetype -3 notitle
