# shares.gp - Luding et al. Fig. 5 bottom: what the contacts hold against
# what the sample gains, each as a share of k_c = k2's (over-consolidated
# at 1000 N/m, sheared at 100 N/m, mu = 0). Data: shares.dat, written by
# scripts/contact-adhesion.py (which also runs this script); by hand:
# gnuplot shares.gp in this folder.
set encoding utf8
set terminal pngcairo size 1000,700 enhanced font "Sans,12"
set output "shares.png"
set datafile missing "?"
set title "Adhesion of the contacts against the strength it adds (p = 100 N/m, over-consolidated at 1000 N/m)"
set xlabel "k_c/k_2"
set ylabel "share of k_c = k_2's"
set grid
set key bottom right box
set xrange [-0.02:1.05]
set yrange [-0.05:1.15]
# columns of shares.dat: 1 k_c/k2, then mean and s.e. of dq_peak (2, 3),
# s_cap_start (4, 5), s_cap_peak (6, 7), s_ten_peak (8, 9), Z_peak
# (10, 11), fmin_peak (12, 13), q_ten_peak (14, 15)
plot 2*x/(1+x) with lines linewidth 2 dashtype 2 linecolor rgb "#7f3fbf" title "f_{min} of one contact, 2x/(1+x)", \
  x with lines linewidth 2 dashtype 3 linecolor rgb "#2a9d8f" title "proportional to k_c", \
  "../oc-fixed-pressure/shares.dat" using ($1-0.012):2:3 with yerrorbars pointtype 7 pointsize 1.4 linecolor rgb "#1f4e9c" title "added peak deviator (oc-* parts, 3-6 seeds)", \
  "shares.dat" using ($1-0.004):2:3 with yerrorbars pointtype 6 pointsize 1.4 linecolor rgb "#1f4e9c" title "added peak deviator (these runs)", \
  "" using ($1+0.004):6:7 with yerrorbars pointtype 5 pointsize 1.3 linecolor rgb "#d62728" title "Σ f_{min} |b|/2A at the peak (what the contacts could hold)", \
  "" using ($1+0.012):8:9 with yerrorbars pointtype 9 pointsize 1.5 linecolor rgb "#e08a00" title "Σ tension |b|/2A at the peak (what they hold)", \
  "" using ($1+0.02):14:15 with yerrorbars pointtype 13 pointsize 1.5 linecolor rgb "#555555" title "deviator of the pairs in tension at the peak"
