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
set xrange [0:3366.91234]
set yrange [0:2020.1474]
plot \
  "mohr_circles.dat" index 0 with lines linewidth 2 linecolor 1 title "p = 100" noenhanced, \
  "mohr_circles.dat" index 1 with lines linewidth 2 linecolor 2 title "p = 250" noenhanced, \
  "mohr_circles.dat" index 2 with lines linewidth 2 linecolor 3 title "p = 500" noenhanced, \
  "mohr_circles.dat" index 3 with lines linewidth 2 linecolor 4 title "p = 1000" noenhanced, \
  "mohr_circles.dat" index 4 with lines dashtype 2 linewidth 2 linecolor "black" title "flow function φ = 30.8°, c = -13.9, R² = 1.000 (seed=1)" noenhanced, \
  "mohr_circles.dat" index 5 with lines linewidth 2 linecolor 1 notitle, \
  "mohr_circles.dat" index 6 with lines linewidth 2 linecolor 2 notitle, \
  "mohr_circles.dat" index 7 with lines linewidth 2 linecolor 3 notitle, \
  "mohr_circles.dat" index 8 with lines linewidth 2 linecolor 4 notitle, \
  "mohr_circles.dat" index 9 with lines dashtype 3 linewidth 2 linecolor "black" title "flow function φ = 29.6°, c = -4.06, R² = 0.999 (seed=2)" noenhanced, \
  "mohr_circles.dat" index 10 with lines linewidth 2 linecolor 1 notitle, \
  "mohr_circles.dat" index 11 with lines linewidth 2 linecolor 2 notitle, \
  "mohr_circles.dat" index 12 with lines linewidth 2 linecolor 3 notitle, \
  "mohr_circles.dat" index 13 with lines linewidth 2 linecolor 4 notitle, \
  "mohr_circles.dat" index 14 with lines dashtype 4 linewidth 2 linecolor "black" title "flow function φ = 29.9°, c = -5.92, R² = 0.999 (seed=3)" noenhanced, \
  "mohr_circles.dat" index 15 with lines linewidth 2 linecolor 1 notitle, \
  "mohr_circles.dat" index 16 with lines linewidth 2 linecolor 2 notitle, \
  "mohr_circles.dat" index 17 with lines linewidth 2 linecolor 3 notitle, \
  "mohr_circles.dat" index 18 with lines linewidth 2 linecolor 4 notitle, \
  "mohr_circles.dat" index 19 with lines dashtype 5 linewidth 2 linecolor "black" title "flow function φ = 30.6°, c = -14.2, R² = 1.000 (seed=4)" noenhanced, \
  0 linetype -3 notitle
