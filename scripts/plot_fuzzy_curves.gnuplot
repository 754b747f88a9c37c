# Accuracy curves of the fuzzy-correspondence runner (bench/runners/fuzzy_benchmark.cpp): one line per column
# of DIR/<name>.dat (column 1 is D, the others are methods, named in the file's second comment line).
# usage: gnuplot -e "name='shrec_curves'; dir='docs/fuzzy'; xlabel='geodesic error D (distance / sqrt(area))'" \
#          scripts/plot_fuzzy_curves.gnuplot
# writes DIR/<name>.png and DIR/<name>.svg
if (!exists("dir")) dir = "."
if (!exists("name")) name = "shrec_curves"
if (!exists("xlabel")) xlabel = "error D"
if (!exists("title_text")) title_text = name
datafile = sprintf("%s/%s.dat", dir, name)
set xlabel xlabel
set ylabel "fraction of correspondences with error <= D"
set xrange [0:0.25]
set yrange [0:1]
set key bottom right
set grid
set title title_text noenhanced
columns = int(system(sprintf("awk '!/^#/ {print NF; exit}' %s", datafile)))
header = system(sprintf("awk 'NR==2 {for (i = 3; i <= NF; ++i) printf \"%%s \", $i}' %s", datafile))
do for [fmt in "png svg"] {
  if (fmt eq "png") { set terminal pngcairo size 800,560 } else { set terminal svg size 800,560 }
  set output sprintf("%s/%s.%s", dir, name, fmt)
  plot for [c = 2:columns] datafile using 1:c with lines lw 2 title word(header, c - 1) noenhanced
}
