# shares.gp - Luding et al. Fig. 5 bottom read at fixed confining pressure:
# what the adhesion adds to the peak deviator, as a share of what
# k_c = k2 adds, against the two candidate shapes. Data: shares.dat, written
# by scripts/reproduction-tables.py docs/reproduction/paper (which also
# runs this script); by hand: gnuplot shares.gp in this folder.
set encoding utf8
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output "shares.png"
set datafile missing "?"
set title "Strength added by the adhesion at fixed pressure (over-consolidated at 1000 N/m, μ = 0)"
set xlabel "k_c/k_2"
set ylabel "added peak deviator / that of k_c = k_2"
set grid
set key top left box
set xrange [-0.02:1.05]
set yrange [-0.05:1.1]
plot 2*x/(1+x) with lines linewidth 2 dashtype 2 title "f_{min} shape, 2x/(1+x)", \
  x with lines linewidth 2 dashtype 3 title "proportional to k_c", \
  "shares.dat" using ($1-0.01):2:3 with yerrorbars pointtype 7 pointsize 1.4 title "p = 100 N/m", \
  "" using 1:4:5 with yerrorbars pointtype 5 pointsize 1.4 title "p = 250 N/m", \
  "" using ($1+0.01):6:7 with yerrorbars pointtype 9 pointsize 1.6 title "p = 500 N/m", \
  "" using ($1+0.02):8:9 with yerrorbars pointtype 11 pointsize 1.6 title "p = 1000 N/m"
