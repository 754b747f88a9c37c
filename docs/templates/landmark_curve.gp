# Landmark correspondence error curve of part-based templates on 200 generated chairs (docs/part_templates.md).
# Data (S200 = the first 200 files of `shapestruct generate chairs 1000 -o S --seed 7`, symlinked with .pts/.seg):
#   run_template_landmarks S200 --template docs/templates/synthetic_chairs.json --threads 1 --curve docs/templates/landmark_curve_set.dat
#   run_template_landmarks S200 --template docs/templates/synthetic_chair.json --threads 1 --curve docs/templates/landmark_curve_one.dat
#   run_template_landmarks S200 --threads 1 --curve docs/templates/landmark_curve_auto.dat   (automatic templates)
# Columns: D, fraction within D through the templates, sampling floor, no-template baseline.
# Plot:   gnuplot -e "dir='docs/templates'" docs/templates/landmark_curve.gp
if (!exists("dir")) dir = 'docs/templates'
set terminal pngcairo size 720,480 font ",11"
set output dir.'/landmark_curve.png'
set xlabel 'D  (Euclidean error / bounding-box diagonal)'
set ylabel 'fraction of landmark pairs within D'
set xrange [0:0.25]
set yrange [0:1.02]
set key bottom right
set grid
plot dir.'/landmark_curve_set.dat' using 1:2 with lines lw 2 title 'template set (seat/back/legs|pedestal, arms, stretchers)', \
     dir.'/landmark_curve_one.dat' using 1:2 with lines lw 2 dt 2 title 'single chair template', \
     dir.'/landmark_curve_auto.dat' using 1:2 with lines lw 2 dt 4 title 'automatic templates (6, learned)', \
     dir.'/landmark_curve_set.dat' using 1:4 with lines lw 1 title 'no template: nearest point after bbox normalisation', \
     dir.'/landmark_curve_set.dat' using 1:3 with lines lw 1 dt 3 title 'sampling floor (1,000 samples)'
