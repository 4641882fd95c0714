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
  "void_ratio_vs_pressure.dat" index 2 with lines linewidth 2 linecolor 1 title "fit initial: e0 = 0.1896, n = 0.567, h_s = 1e+05, R² = 0.992 (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 3 with lines linewidth 2 linecolor 2 title "fit critical: e0 = 0.2555, n = 0.480, h_s = 1e+05, R² = 0.997 (seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 4 with points pointtype 6 pointsize 1.5 linecolor 3 title "initial (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 5 with points pointtype 7 pointsize 1.5 linecolor 4 title "critical (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 6 with lines linewidth 2 linecolor 3 title "fit initial: e0 = 0.1914, n = 0.548, h_s = 1e+05, R² = 0.999 (seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 8 with points pointtype 6 pointsize 1.5 linecolor 5 title "initial (seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 9 with points pointtype 7 pointsize 1.5 linecolor 6 title "critical (seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 10 with lines linewidth 2 linecolor 5 title "fit initial: e0 = 0.1912, n = 0.555, h_s = 1e+05, R² = 0.990 (seed=3)" noenhanced, \
  0 linetype -3 notitle
