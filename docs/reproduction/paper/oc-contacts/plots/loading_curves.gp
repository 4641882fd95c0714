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
set clip two
set terminal pngcairo size 1000,1100 enhanced font "Sans,12"
set output outfile
unset title
set key outside right top
set tmargin 5
set multiplot layout 2,1 title "Loading curves: the loading stage of every run"
set ylabel "volumetric strain ε_v (expansion > 0)"
plot 'loading_curves.dat' index 0 using 1:2 with lines lc 1 noenhanced title "contact.kc=0.0 (2 runs)", \
  'loading_curves.dat' index 1 using 1:2 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 2 using 1:2 with lines lc 2 noenhanced title "contact.kc=2.5e4 (2 runs)", \
  'loading_curves.dat' index 3 using 1:2 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 4 using 1:2 with lines lc 3 noenhanced title "contact.kc=5.0e4 (2 runs)", \
  'loading_curves.dat' index 5 using 1:2 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 6 using 1:2 with lines lc 4 noenhanced title "contact.kc=7.5e4 (2 runs)", \
  'loading_curves.dat' index 7 using 1:2 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 8 using 1:2 with lines lc 5 noenhanced title "contact.kc=1.0e5 (2 runs)", \
  'loading_curves.dat' index 9 using 1:2 with lines lc 5 noenhanced notitle
set ylabel "σ_{axial} - σ_{lateral} (Pa; 2D: N/m)"
plot 'loading_curves.dat' index 0 using 1:3 with lines lc 1 noenhanced title "contact.kc=0.0 (2 runs)", \
  'loading_curves.dat' index 1 using 1:3 with lines lc 1 noenhanced notitle, \
  'loading_curves.dat' index 2 using 1:3 with lines lc 2 noenhanced title "contact.kc=2.5e4 (2 runs)", \
  'loading_curves.dat' index 3 using 1:3 with lines lc 2 noenhanced notitle, \
  'loading_curves.dat' index 4 using 1:3 with lines lc 3 noenhanced title "contact.kc=5.0e4 (2 runs)", \
  'loading_curves.dat' index 5 using 1:3 with lines lc 3 noenhanced notitle, \
  'loading_curves.dat' index 6 using 1:3 with lines lc 4 noenhanced title "contact.kc=7.5e4 (2 runs)", \
  'loading_curves.dat' index 7 using 1:3 with lines lc 4 noenhanced notitle, \
  'loading_curves.dat' index 8 using 1:3 with lines lc 5 noenhanced title "contact.kc=1.0e5 (2 runs)", \
  'loading_curves.dat' index 9 using 1:3 with lines lc 5 noenhanced notitle
unset multiplot
