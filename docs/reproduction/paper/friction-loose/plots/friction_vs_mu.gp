# friction_vs_mu.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot friction_vs_mu.gp
# The data are in friction_vs_mu.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "friction_vs_mu.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Macroscopic friction at peak and in critical state"
set xlabel "microscopic friction μ"
set ylabel "sin φ = (σ_1 - σ_3)/(σ_1 + σ_3)"
set grid
set key below box
set clip two
set xrange [0:*]
set yrange [0:*]
plot \
  "friction_vs_mu.dat" index 0 using 1:2:3 with yerrorlines pointtype 6 pointsize 1.5 linecolor 1 title "peak, mean ± s.e." noenhanced, \
  "" index 0 using 1:4:5 with yerrorlines pointtype 7 pointsize 1.5 linecolor 1 title "critical state, mean ± s.e." noenhanced, \
  0 linetype -3 notitle
