# Work-precision diagram of bench/work_precision.sh:
#   gnuplot -e "data='CURVES.dat'; out='FILE.png'; blocks=N" bench/work_precision.gp
# CURVES.dat has N blocks, one per curve (first line: its title), each
# point the solver's wall time (s), the largest error over the outputs
# and the rtol.
set terminal pngcairo size 1000,760 font ",11"
set output out
set logscale xy
set format x "10^{%T}"
set format y "10^{%T}"
set xlabel "solver wall time (s), least of the runs"
set ylabel "max over outputs of max_t |y - y_{ref}| / range(y_{ref})"
set title "examples/apc6x6.yaml, 15 s at 1 kHz: rtol 1e-4 ... 1e-8, atol = rtol/100"
set grid
set key below vertical maxrows 4 Left reverse noenhanced
set linetype 1 lc rgb "#1f77b4" pt 7
set linetype 2 lc rgb "#2ca02c" pt 5
set linetype 3 lc rgb "#ff7f0e" pt 9
set linetype 4 lc rgb "#d62728" pt 11
set linetype 5 lc rgb "#9467bd" pt 13
set linetype 6 lc rgb "#8c564b" pt 15
set linetype 7 lc rgb "#7f7f7f" pt 6
plot for [i=0:blocks-1] data index i using 1:2 with linespoints lw 2 ps 1.3 title columnheader(1)
