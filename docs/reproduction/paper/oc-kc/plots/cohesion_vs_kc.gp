# cohesion_vs_kc.gp - written by dembox; edit freely and re-run in this folder:
#     gnuplot cohesion_vs_kc.gp
# The data are in cohesion_vs_kc.dat (columns described in its header).
set encoding utf8
if (!exists("outfile")) outfile = "cohesion_vs_kc.png"
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output outfile
set datafile missing "?"
set title "Macroscopic cohesion versus k_c/k_2 (flow functions at peak)"
set xlabel "k_c/k_2"
set ylabel "cohesion c"
set grid
set key below box
set xrange [0:0.55]
plot "cohesion_vs_kc.dat" index 0 using 1:2:3 with yerrorbars pointtype 7 pointsize 1.5 title "flow functions, mean ± s.e. over the seeds", \
  "" index 1 with lines linewidth 2 title "A |f_{min}|/(k_2 δ_{max}) (A fitted)"
