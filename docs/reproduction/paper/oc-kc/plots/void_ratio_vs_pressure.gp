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
plot \
  "void_ratio_vs_pressure.dat" index 0 with points pointtype 6 pointsize 1.5 linecolor 1 title "initial (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 1 with points pointtype 7 pointsize 1.5 linecolor 2 title "critical (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 2 with lines linewidth 2 linecolor 1 title "fit initial: e0 = 0.1624, n = 0.743, h_s = 1e+05, R² = 0.999 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 3 with lines linewidth 2 linecolor 2 title "fit critical: e0 = 0.2242, n = 0.493, h_s = 1e+05, R² = 0.999 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 4 with points pointtype 6 pointsize 1.5 linecolor 3 title "initial (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 5 with points pointtype 7 pointsize 1.5 linecolor 4 title "critical (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 6 with lines linewidth 2 linecolor 3 title "fit initial: e0 = 0.1657, n = 0.744, h_s = 1e+05, R² = 0.999 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 8 with points pointtype 6 pointsize 1.5 linecolor 5 title "initial (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 9 with points pointtype 7 pointsize 1.5 linecolor 6 title "critical (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 10 with lines linewidth 2 linecolor 5 title "fit initial: e0 = 0.1591, n = 0.751, h_s = 1e+05, R² = 0.998 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 11 with lines linewidth 2 linecolor 6 title "fit critical: e0 = 0.2177, n = 0.508, h_s = 1e+05, R² = 0.997 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 12 with points pointtype 6 pointsize 1.5 linecolor 7 title "initial (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 13 with points pointtype 7 pointsize 1.5 linecolor 8 title "critical (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 14 with lines linewidth 2 linecolor 7 title "fit initial: e0 = 0.1636, n = 0.746, h_s = 1e+05, R² = 0.999 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 15 with lines linewidth 2 linecolor 8 title "fit critical: e0 = 0.2500, n = 0.442, h_s = 1e+05, R² = 1.000 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 16 with points pointtype 6 pointsize 1.5 linecolor 9 title "initial (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 17 with points pointtype 7 pointsize 1.5 linecolor 10 title "critical (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 18 with lines linewidth 2 linecolor 9 title "fit initial: e0 = 0.1611, n = 0.751, h_s = 1e+05, R² = 0.998 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 19 with lines linewidth 2 linecolor 10 title "fit critical: e0 = 0.2482, n = 0.447, h_s = 1e+05, R² = 0.999 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 20 with points pointtype 6 pointsize 1.5 linecolor 11 title "initial (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 21 with points pointtype 7 pointsize 1.5 linecolor 12 title "critical (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 22 with lines linewidth 2 linecolor 11 title "fit initial: e0 = 0.1634, n = 0.744, h_s = 1e+05, R² = 0.999 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 23 with lines linewidth 2 linecolor 12 title "fit critical: e0 = 0.2563, n = 0.432, h_s = 1e+05, R² = 0.995 (contact.kc=5.0e4, seed=3)" noenhanced, \
  0 linetype -3 notitle
