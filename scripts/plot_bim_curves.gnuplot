# Accuracy curves of the BIM benchmark runner (bench/runners/bim_benchmark.cpp).
# usage: gnuplot -e "set_name='scape'; dir='docs/blended_maps'" scripts/plot_bim_curves.gnuplot
#        (optional: note='...' is added to the title)
# reads DIR/<set>_curves.dat, writes DIR/<set>_curves.png and DIR/<set>_curves.svg
# The error is the benchmark's, geodesic distance / sqrt(area of the target) (the runner's and the stored results').
if (!exists("dir")) dir = "."
if (!exists("set_name")) set_name = "scape"
datafile = sprintf("%s/%s_curves.dat", dir, set_name)
set xlabel "geodesic error D (distance / sqrt(area))"
set ylabel "fraction of correspondences with error <= D"
set xrange [0:0.25]
set yrange [0:1]
set key bottom right
set grid
if (!exists("note")) note = ""
set title sprintf("Blended intrinsic maps, %s%s", set_name, note) noenhanced
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 800,560 } else { set terminal svg size 800,560 }
  set output sprintf("%s/%s_curves.%s", dir, set_name, fmt)
  plot datafile using 1:2 with lines lw 2 lc rgb "#1f77b4" title "shapestruct (raw)", \
       datafile using 1:3 with lines lw 2 dt 2 lc rgb "#1f77b4" title "shapestruct (with flips)", \
       datafile using 1:4 with lines lw 2 lc rgb "#d62728" title "original BIM, stored (raw)", \
       datafile using 1:5 with lines lw 2 dt 2 lc rgb "#d62728" title "original BIM, stored (with flips)"
}
