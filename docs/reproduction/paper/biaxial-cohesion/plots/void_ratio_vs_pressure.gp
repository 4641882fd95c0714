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
  "void_ratio_vs_pressure.dat" index 0 with points pointtype 6 pointsize 1.5 linecolor 1 title "initial (contact.kc=0.0, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 1 with points pointtype 7 pointsize 1.5 linecolor 2 title "critical (contact.kc=0.0, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 2 with lines linewidth 2 linecolor 1 title "fit initial: e0 = 0.2076, n = 0.552, h_s = 1e+05, R² = 0.998 (contact.kc=0.0, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 3 with lines linewidth 2 linecolor 2 title "fit critical: e0 = 0.2155, n = 0.514, h_s = 1e+05, R² = 0.997 (contact.kc=0.0, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 4 with points pointtype 6 pointsize 1.5 linecolor 3 title "initial (contact.kc=0.0, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 5 with points pointtype 7 pointsize 1.5 linecolor 4 title "critical (contact.kc=0.0, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 6 with lines linewidth 2 linecolor 3 title "fit initial: e0 = 0.2030, n = 0.574, h_s = 1e+05, R² = 0.982 (contact.kc=0.0, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 7 with lines linewidth 2 linecolor 4 title "fit critical: e0 = 0.2050, n = 0.565, h_s = 1e+05, R² = 0.997 (contact.kc=0.0, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 8 with points pointtype 6 pointsize 1.5 linecolor 5 title "initial (contact.kc=0.0, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 9 with points pointtype 7 pointsize 1.5 linecolor 6 title "critical (contact.kc=0.0, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 10 with lines linewidth 2 linecolor 5 title "fit initial: e0 = 0.2034, n = 0.570, h_s = 1e+05, R² = 0.996 (contact.kc=0.0, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 11 with lines linewidth 2 linecolor 6 title "fit critical: e0 = 0.2145, n = 0.523, h_s = 1e+05, R² = 0.986 (contact.kc=0.0, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 12 with points pointtype 6 pointsize 1.5 linecolor 7 title "initial (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 13 with points pointtype 7 pointsize 1.5 linecolor 8 title "critical (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 14 with lines linewidth 2 linecolor 7 title "fit initial: e0 = 0.2034, n = 0.569, h_s = 1e+05, R² = 0.999 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 15 with lines linewidth 2 linecolor 8 title "fit critical: e0 = 0.2168, n = 0.511, h_s = 1e+05, R² = 0.993 (contact.kc=2.5e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 16 with points pointtype 6 pointsize 1.5 linecolor 9 title "initial (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 17 with points pointtype 7 pointsize 1.5 linecolor 10 title "critical (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 18 with lines linewidth 2 linecolor 9 title "fit initial: e0 = 0.1995, n = 0.591, h_s = 1e+05, R² = 0.999 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 19 with lines linewidth 2 linecolor 10 title "fit critical: e0 = 0.2244, n = 0.491, h_s = 1e+05, R² = 0.996 (contact.kc=2.5e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 20 with points pointtype 6 pointsize 1.5 linecolor 11 title "initial (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 21 with points pointtype 7 pointsize 1.5 linecolor 12 title "critical (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 22 with lines linewidth 2 linecolor 11 title "fit initial: e0 = 0.2052, n = 0.561, h_s = 1e+05, R² = 0.985 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 23 with lines linewidth 2 linecolor 12 title "fit critical: e0 = 0.2256, n = 0.486, h_s = 1e+05, R² = 0.997 (contact.kc=2.5e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 24 with points pointtype 6 pointsize 1.5 linecolor 13 title "initial (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 25 with points pointtype 7 pointsize 1.5 linecolor 14 title "critical (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 26 with lines linewidth 2 linecolor 13 title "fit initial: e0 = 0.2068, n = 0.565, h_s = 1e+05, R² = 0.997 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 27 with lines linewidth 2 linecolor 14 title "fit critical: e0 = 0.2360, n = 0.470, h_s = 1e+05, R² = 0.995 (contact.kc=5.0e4, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 28 with points pointtype 6 pointsize 1.5 linecolor 15 title "initial (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 29 with points pointtype 7 pointsize 1.5 linecolor 16 title "critical (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 30 with lines linewidth 2 linecolor 15 title "fit initial: e0 = 0.2063, n = 0.558, h_s = 1e+05, R² = 0.998 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 31 with lines linewidth 2 linecolor 16 title "fit critical: e0 = 0.2310, n = 0.480, h_s = 1e+05, R² = 0.997 (contact.kc=5.0e4, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 32 with points pointtype 6 pointsize 1.5 linecolor 17 title "initial (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 33 with points pointtype 7 pointsize 1.5 linecolor 18 title "critical (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 34 with lines linewidth 2 linecolor 17 title "fit initial: e0 = 0.2039, n = 0.570, h_s = 1e+05, R² = 0.998 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 35 with lines linewidth 2 linecolor 18 title "fit critical: e0 = 0.2307, n = 0.480, h_s = 1e+05, R² = 0.996 (contact.kc=5.0e4, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 36 with points pointtype 6 pointsize 1.5 linecolor 19 title "initial (contact.kc=1.0e5, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 37 with points pointtype 7 pointsize 1.5 linecolor 20 title "critical (contact.kc=1.0e5, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 38 with lines linewidth 2 linecolor 19 title "fit initial: e0 = 0.2075, n = 0.562, h_s = 1e+05, R² = 0.980 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 39 with lines linewidth 2 linecolor 20 title "fit critical: e0 = 0.2442, n = 0.457, h_s = 1e+05, R² = 0.994 (contact.kc=1.0e5, seed=1)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 40 with points pointtype 6 pointsize 1.5 linecolor 21 title "initial (contact.kc=1.0e5, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 41 with points pointtype 7 pointsize 1.5 linecolor 22 title "critical (contact.kc=1.0e5, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 42 with lines linewidth 2 linecolor 21 title "fit initial: e0 = 0.2149, n = 0.533, h_s = 1e+05, R² = 0.996 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 43 with lines linewidth 2 linecolor 22 title "fit critical: e0 = 0.2751, n = 0.405, h_s = 1e+05, R² = 0.999 (contact.kc=1.0e5, seed=2)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 44 with points pointtype 6 pointsize 1.5 linecolor 23 title "initial (contact.kc=1.0e5, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 45 with points pointtype 7 pointsize 1.5 linecolor 24 title "critical (contact.kc=1.0e5, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 46 with lines linewidth 2 linecolor 23 title "fit initial: e0 = 0.2105, n = 0.551, h_s = 1e+05, R² = 0.998 (contact.kc=1.0e5, seed=3)" noenhanced, \
  "void_ratio_vs_pressure.dat" index 47 with lines linewidth 2 linecolor 24 title "fit critical: e0 = 0.2496, n = 0.446, h_s = 1e+05, R² = 0.991 (contact.kc=1.0e5, seed=3)" noenhanced, \
  0 linetype -3 notitle
