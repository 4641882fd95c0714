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
set size ratio -1
set xrange [0:1886.16]
set yrange [0:1131.7]
plot \
  "mohr_circles.dat" index 0 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=0.0, seed=1)" noenhanced, \
  "mohr_circles.dat" index 1 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=0.0, seed=1)" noenhanced, \
  "mohr_circles.dat" index 2 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=0.0, seed=1)" noenhanced, \
  "mohr_circles.dat" index 3 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=0.0, seed=1)" noenhanced, \
  "mohr_circles.dat" index 4 with lines dashtype 2 linewidth 2 linecolor "black" title "flow function φ = 10.0°, c = -2.63, R² = 1.000 (contact.kc=0.0, seed=1)" noenhanced, \
  "mohr_circles.dat" index 5 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=0.0, seed=2)" noenhanced, \
  "mohr_circles.dat" index 6 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=0.0, seed=2)" noenhanced, \
  "mohr_circles.dat" index 7 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=0.0, seed=2)" noenhanced, \
  "mohr_circles.dat" index 8 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=0.0, seed=2)" noenhanced, \
  "mohr_circles.dat" index 9 with lines dashtype 3 linewidth 2 linecolor "black" title "flow function φ = 9.2°, c = 3.12, R² = 0.996 (contact.kc=0.0, seed=2)" noenhanced, \
  "mohr_circles.dat" index 10 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=0.0, seed=3)" noenhanced, \
  "mohr_circles.dat" index 11 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=0.0, seed=3)" noenhanced, \
  "mohr_circles.dat" index 12 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=0.0, seed=3)" noenhanced, \
  "mohr_circles.dat" index 13 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=0.0, seed=3)" noenhanced, \
  "mohr_circles.dat" index 14 with lines dashtype 4 linewidth 2 linecolor "black" title "flow function φ = 9.8°, c = -1.97, R² = 0.998 (contact.kc=0.0, seed=3)" noenhanced, \
  "mohr_circles.dat" index 15 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 16 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 17 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 18 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 19 with lines dashtype 5 linewidth 2 linecolor "black" title "flow function φ = 10.0°, c = 2.61, R² = 0.999 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 20 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 21 with lines linewidth 2 linecolor 2 title "p = 1000 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 22 with lines dashtype 6 linewidth 2 linecolor "black" title "flow function φ = 10.2°, c = 1.32, R² = 1.000 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 23 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 24 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 25 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 26 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 27 with lines dashtype 7 linewidth 2 linecolor "black" title "flow function φ = 11.0°, c = -4.67, R² = 1.000 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 28 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 29 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 30 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 31 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 32 with lines dashtype 8 linewidth 2 linecolor "black" title "flow function φ = 11.7°, c = 2.28, R² = 0.999 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "mohr_circles.dat" index 33 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 34 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 35 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 36 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 37 with lines dashtype 9 linewidth 2 linecolor "black" title "flow function φ = 11.4°, c = 4.68, R² = 0.999 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "mohr_circles.dat" index 38 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 39 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 40 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 41 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 42 with lines dashtype 10 linewidth 2 linecolor "black" title "flow function φ = 13.1°, c = -7.51, R² = 0.997 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "mohr_circles.dat" index 43 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "mohr_circles.dat" index 44 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "mohr_circles.dat" index 45 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "mohr_circles.dat" index 46 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "mohr_circles.dat" index 47 with lines dashtype 11 linewidth 2 linecolor "black" title "flow function φ = 14.5°, c = 0.392, R² = 1.000 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "mohr_circles.dat" index 48 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "mohr_circles.dat" index 49 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "mohr_circles.dat" index 50 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "mohr_circles.dat" index 51 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "mohr_circles.dat" index 52 with lines dashtype 12 linewidth 2 linecolor "black" title "flow function φ = 15.4°, c = -3.12, R² = 0.999 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "mohr_circles.dat" index 53 with lines linewidth 2 linecolor 1 title "p = 100 (contact.kc=1.0e5, seed=3)" noenhanced, \
  "mohr_circles.dat" index 54 with lines linewidth 2 linecolor 2 title "p = 250 (contact.kc=1.0e5, seed=3)" noenhanced, \
  "mohr_circles.dat" index 55 with lines linewidth 2 linecolor 3 title "p = 500 (contact.kc=1.0e5, seed=3)" noenhanced, \
  "mohr_circles.dat" index 56 with lines linewidth 2 linecolor 4 title "p = 1000 (contact.kc=1.0e5, seed=3)" noenhanced, \
  "mohr_circles.dat" index 57 with lines dashtype 13 linewidth 2 linecolor "black" title "flow function φ = 14.1°, c = 3.15, R² = 1.000 (contact.kc=1.0e5, seed=3)" noenhanced, \
  0 linetype -3 notitle
