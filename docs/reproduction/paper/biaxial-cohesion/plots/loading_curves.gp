# loading_curves.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot loading_curves.gp
# The data are in loading_curves.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "loading_curves.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title ""
set xlabel "axial strain"
set ylabel ""
set grid
set key below box
set terminal pngcairo size 1000,1100 enhanced font "Sans,12"
set output outfile
unset title
set key outside right top
set tmargin 5
set multiplot layout 2,1 title "Loading curves: the loading stage of every run"
set ylabel "volumetric strain ε_v (expansion > 0)"
plot 'loading_curves.dat' index 0 using 1:2 with lines lc 1 noenhanced title "contact.kc=0.0, stages.0.pressure=100", \
  'loading_curves.dat' index 1 using 1:2 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 2 using 1:2 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 3 using 1:2 with lines lc 2 noenhanced title "contact.kc=0.0, stages.0.pressure=250", \
  'loading_curves.dat' index 4 using 1:2 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 5 using 1:2 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 6 using 1:2 with lines lc 3 noenhanced title "contact.kc=0.0, stages.0.pressure=500", \
  'loading_curves.dat' index 7 using 1:2 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 8 using 1:2 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 9 using 1:2 with lines lc 4 noenhanced title "contact.kc=0.0, stages.0.pressure=1000", \
  'loading_curves.dat' index 10 using 1:2 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 11 using 1:2 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 12 using 1:2 with lines lc 5 noenhanced title "contact.kc=2.5e4, stages.0.pressure=100", \
  'loading_curves.dat' index 13 using 1:2 with lines lc 5 noenhanced notitle, \
  'loading_curves.dat' index 14 using 1:2 with lines lc 5 noenhanced notitle, \
  'loading_curves.dat' index 15 using 1:2 with lines lc 6 noenhanced title "contact.kc=2.5e4, stages.0.pressure=250", \
  'loading_curves.dat' index 16 using 1:2 with lines lc 6 noenhanced notitle, \
  'loading_curves.dat' index 17 using 1:2 with lines lc 6 noenhanced notitle, \
  'loading_curves.dat' index 18 using 1:2 with lines lc 7 noenhanced title "contact.kc=2.5e4, stages.0.pressure=500", \
  'loading_curves.dat' index 19 using 1:2 with lines lc 7 noenhanced notitle, \
  'loading_curves.dat' index 20 using 1:2 with lines lc 7 noenhanced notitle, \
  'loading_curves.dat' index 21 using 1:2 with lines lc 8 noenhanced title "contact.kc=2.5e4, stages.0.pressure=1000", \
  'loading_curves.dat' index 22 using 1:2 with lines lc 8 noenhanced notitle, \
  'loading_curves.dat' index 23 using 1:2 with lines lc 8 noenhanced notitle, \
  'loading_curves.dat' index 24 using 1:2 with lines lc 9 noenhanced title "contact.kc=5.0e4, stages.0.pressure=100", \
  'loading_curves.dat' index 25 using 1:2 with lines lc 9 noenhanced notitle, \
  'loading_curves.dat' index 26 using 1:2 with lines lc 9 noenhanced notitle, \
  'loading_curves.dat' index 27 using 1:2 with lines lc 10 noenhanced title "contact.kc=5.0e4, stages.0.pressure=250", \
  'loading_curves.dat' index 28 using 1:2 with lines lc 10 noenhanced notitle, \
  'loading_curves.dat' index 29 using 1:2 with lines lc 10 noenhanced notitle, \
  'loading_curves.dat' index 30 using 1:2 with lines lc 11 noenhanced title "contact.kc=5.0e4, stages.0.pressure=500", \
  'loading_curves.dat' index 31 using 1:2 with lines lc 11 noenhanced notitle, \
  'loading_curves.dat' index 32 using 1:2 with lines lc 11 noenhanced notitle, \
  'loading_curves.dat' index 33 using 1:2 with lines lc 12 noenhanced title "contact.kc=5.0e4, stages.0.pressure=1000", \
  'loading_curves.dat' index 34 using 1:2 with lines lc 12 noenhanced notitle, \
  'loading_curves.dat' index 35 using 1:2 with lines lc 12 noenhanced notitle, \
  'loading_curves.dat' index 36 using 1:2 with lines lc 13 noenhanced title "contact.kc=1.0e5, stages.0.pressure=100", \
  'loading_curves.dat' index 37 using 1:2 with lines lc 13 noenhanced notitle, \
  'loading_curves.dat' index 38 using 1:2 with lines lc 13 noenhanced notitle, \
  'loading_curves.dat' index 39 using 1:2 with lines lc 14 noenhanced title "contact.kc=1.0e5, stages.0.pressure=250", \
  'loading_curves.dat' index 40 using 1:2 with lines lc 14 noenhanced notitle, \
  'loading_curves.dat' index 41 using 1:2 with lines lc 14 noenhanced notitle, \
  'loading_curves.dat' index 42 using 1:2 with lines lc 15 noenhanced title "contact.kc=1.0e5, stages.0.pressure=500", \
  'loading_curves.dat' index 43 using 1:2 with lines lc 15 noenhanced notitle, \
  'loading_curves.dat' index 44 using 1:2 with lines lc 15 noenhanced notitle, \
  'loading_curves.dat' index 45 using 1:2 with lines lc 16 noenhanced title "contact.kc=1.0e5, stages.0.pressure=1000", \
  'loading_curves.dat' index 46 using 1:2 with lines lc 16 noenhanced notitle, \
  'loading_curves.dat' index 47 using 1:2 with lines lc 16 noenhanced notitle
set ylabel "σ_{axial} - σ_{lateral} (Pa; 2D: N/m)"
plot 'loading_curves.dat' index 0 using 1:3 with lines lc 1 noenhanced title "contact.kc=0.0, stages.0.pressure=100", \
  'loading_curves.dat' index 1 using 1:3 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 2 using 1:3 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 3 using 1:3 with lines lc 2 noenhanced title "contact.kc=0.0, stages.0.pressure=250", \
  'loading_curves.dat' index 4 using 1:3 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 5 using 1:3 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 6 using 1:3 with lines lc 3 noenhanced title "contact.kc=0.0, stages.0.pressure=500", \
  'loading_curves.dat' index 7 using 1:3 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 8 using 1:3 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 9 using 1:3 with lines lc 4 noenhanced title "contact.kc=0.0, stages.0.pressure=1000", \
  'loading_curves.dat' index 10 using 1:3 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 11 using 1:3 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 12 using 1:3 with lines lc 5 noenhanced title "contact.kc=2.5e4, stages.0.pressure=100", \
  'loading_curves.dat' index 13 using 1:3 with lines lc 5 noenhanced notitle, \
  'loading_curves.dat' index 14 using 1:3 with lines lc 5 noenhanced notitle, \
  'loading_curves.dat' index 15 using 1:3 with lines lc 6 noenhanced title "contact.kc=2.5e4, stages.0.pressure=250", \
  'loading_curves.dat' index 16 using 1:3 with lines lc 6 noenhanced notitle, \
  'loading_curves.dat' index 17 using 1:3 with lines lc 6 noenhanced notitle, \
  'loading_curves.dat' index 18 using 1:3 with lines lc 7 noenhanced title "contact.kc=2.5e4, stages.0.pressure=500", \
  'loading_curves.dat' index 19 using 1:3 with lines lc 7 noenhanced notitle, \
  'loading_curves.dat' index 20 using 1:3 with lines lc 7 noenhanced notitle, \
  'loading_curves.dat' index 21 using 1:3 with lines lc 8 noenhanced title "contact.kc=2.5e4, stages.0.pressure=1000", \
  'loading_curves.dat' index 22 using 1:3 with lines lc 8 noenhanced notitle, \
  'loading_curves.dat' index 23 using 1:3 with lines lc 8 noenhanced notitle, \
  'loading_curves.dat' index 24 using 1:3 with lines lc 9 noenhanced title "contact.kc=5.0e4, stages.0.pressure=100", \
  'loading_curves.dat' index 25 using 1:3 with lines lc 9 noenhanced notitle, \
  'loading_curves.dat' index 26 using 1:3 with lines lc 9 noenhanced notitle, \
  'loading_curves.dat' index 27 using 1:3 with lines lc 10 noenhanced title "contact.kc=5.0e4, stages.0.pressure=250", \
  'loading_curves.dat' index 28 using 1:3 with lines lc 10 noenhanced notitle, \
  'loading_curves.dat' index 29 using 1:3 with lines lc 10 noenhanced notitle, \
  'loading_curves.dat' index 30 using 1:3 with lines lc 11 noenhanced title "contact.kc=5.0e4, stages.0.pressure=500", \
  'loading_curves.dat' index 31 using 1:3 with lines lc 11 noenhanced notitle, \
  'loading_curves.dat' index 32 using 1:3 with lines lc 11 noenhanced notitle, \
  'loading_curves.dat' index 33 using 1:3 with lines lc 12 noenhanced title "contact.kc=5.0e4, stages.0.pressure=1000", \
  'loading_curves.dat' index 34 using 1:3 with lines lc 12 noenhanced notitle, \
  'loading_curves.dat' index 35 using 1:3 with lines lc 12 noenhanced notitle, \
  'loading_curves.dat' index 36 using 1:3 with lines lc 13 noenhanced title "contact.kc=1.0e5, stages.0.pressure=100", \
  'loading_curves.dat' index 37 using 1:3 with lines lc 13 noenhanced notitle, \
  'loading_curves.dat' index 38 using 1:3 with lines lc 13 noenhanced notitle, \
  'loading_curves.dat' index 39 using 1:3 with lines lc 14 noenhanced title "contact.kc=1.0e5, stages.0.pressure=250", \
  'loading_curves.dat' index 40 using 1:3 with lines lc 14 noenhanced notitle, \
  'loading_curves.dat' index 41 using 1:3 with lines lc 14 noenhanced notitle, \
  'loading_curves.dat' index 42 using 1:3 with lines lc 15 noenhanced title "contact.kc=1.0e5, stages.0.pressure=500", \
  'loading_curves.dat' index 43 using 1:3 with lines lc 15 noenhanced notitle, \
  'loading_curves.dat' index 44 using 1:3 with lines lc 15 noenhanced notitle, \
  'loading_curves.dat' index 45 using 1:3 with lines lc 16 noenhanced title "contact.kc=1.0e5, stages.0.pressure=1000", \
  'loading_curves.dat' index 46 using 1:3 with lines lc 16 noenhanced notitle, \
  'loading_curves.dat' index 47 using 1:3 with lines lc 16 noenhanced notitle
unset multiplot
