# stress_ratio_vs_void_ratio.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot stress_ratio_vs_void_ratio.gp
# The data are in stress_ratio_vs_void_ratio.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "stress_ratio_vs_void_ratio.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Stress ratio versus void ratio during loading"
set xlabel "void ratio e"
set ylabel "sin φ_m = (σ_1 - σ_3)/(σ_1 + σ_3)"
set grid
set key below box
set clip two
plot \
  "stress_ratio_vs_void_ratio.dat" index 0 with lines title "p = 100 (seed=1)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 1 with lines title "p = 100 (seed=2)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 2 with lines title "p = 100 (seed=3)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 3 with lines title "p = 100 (seed=4)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 4 with lines title "p = 250 (seed=1)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 5 with lines title "p = 250 (seed=2)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 6 with lines title "p = 250 (seed=3)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 7 with lines title "p = 250 (seed=4)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 8 with lines title "p = 500 (seed=1)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 9 with lines title "p = 500 (seed=2)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 10 with lines title "p = 500 (seed=3)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 11 with lines title "p = 500 (seed=4)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 12 with lines title "p = 1000 (seed=1)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 13 with lines title "p = 1000 (seed=2)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 14 with lines title "p = 1000 (seed=3)" noenhanced, \
  "stress_ratio_vs_void_ratio.dat" index 15 with lines title "p = 1000 (seed=4)" noenhanced, \
  0 linetype -3 notitle
