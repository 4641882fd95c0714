# void_ratio_vs_pressure.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot void_ratio_vs_pressure.gp
# The data are in void_ratio_vs_pressure.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "void_ratio_vs_pressure.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Void ratio versus pressure, fits e = e_0 - (p/h_s)^n"
set xlabel "pressure p"
set ylabel "void ratio e"
set grid
set key below box
set clip two
plot \
  "void_ratio_vs_pressure.dat" index 0 with points pointtype 6 pointsize 1.5 linecolor 1 title "initial (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 1 with points pointtype 7 pointsize 1.5 linecolor 2 title "critical (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 2 with lines linewidth 2 linecolor 1 title "fit initial: e0 = 0.2017, n = 0.551, h_s = 1e+05, R² = 0.988 (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 3 with lines linewidth 2 linecolor 2 title "fit critical: e0 = 0.2465, n = 0.530, h_s = 1e+05, R² = 0.944 (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 4 with points pointtype 6 pointsize 1.5 linecolor 3 title "initial (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 5 with points pointtype 7 pointsize 1.5 linecolor 4 title "critical (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 6 with lines linewidth 2 linecolor 3 title "fit initial: e0 = 1.0111, n = 0.027, h_s = 1e+05, R² = 0.974 (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 8 with points pointtype 6 pointsize 1.5 linecolor 5 title "initial (seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 9 with points pointtype 7 pointsize 1.5 linecolor 6 title "critical (seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 10 with lines linewidth 2 linecolor 5 title "fit initial: e0 = 0.2015, n = 0.550, h_s = 1e+05, R² = 0.992 (seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 12 with points pointtype 6 pointsize 1.5 linecolor 7 title "initial (seed=4)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 13 with points pointtype 7 pointsize 1.5 linecolor 8 title "critical (seed=4)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 14 with lines linewidth 2 linecolor 7 title "fit initial: e0 = 0.2007, n = 0.550, h_s = 1e+05, R² = 0.983 (seed=4)" noenhanced, \
  0 linetype -3 notitle
