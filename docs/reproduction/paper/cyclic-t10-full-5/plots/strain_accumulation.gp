# strain_accumulation.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot strain_accumulation.gp
# The data are in strain_accumulation.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "strain_accumulation.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Strain accumulated per cycle"
set xlabel "cycle c"
set ylabel "Δε_D per cycle"
set grid
set key below box
set clip two
set multiplot layout 1,2 title "Strain accumulation"
set logscale xy
set format y "%.0e"
unset title
set key inside top left box opaque font ",10"
set ylabel "ε_D at the end of cycle c"
plot \
  "strain_accumulation.dat" index 0 using 1:($4 > 0 ? $4 : 1/0):5 with yerrorlines pointtype 7 pointsize 0.6 linecolor 1 title "verdict: shakedown" noenhanced, \
  "" index 0 using 1:($4 < 0 ? -$4 : 1/0):5 with yerrorbars pointtype 6 pointsize 0.9 linecolor 1 notitle, \
  1/0 with points pointtype 6 pointsize 0.9 linecolor "black" title "open: negative, |value| drawn" noenhanced, \
  1/0 notitle
unset key
set ylabel "Δε_D gained in cycle c"
plot \
  "strain_accumulation.dat" index 0 using 1:($2 > 0 ? $2 : 1/0):3 with yerrorlines pointtype 7 pointsize 0.6 linecolor 1 title "verdict: shakedown" noenhanced, \
  "" index 0 using 1:($2 < 0 ? -$2 : 1/0):3 with yerrorbars pointtype 6 pointsize 0.9 linecolor 1 notitle, \
  1/0 with points pointtype 6 pointsize 0.9 linecolor "black" title "open: negative, |value| drawn" noenhanced, \
  1/0 notitle
unset multiplot
