# Plots of a benchmark run: gnuplot -e "dir='bench/out'" bench/plots.gp
# Reads the CSV files the bench programs wrote into dir and writes PNG files beside them.
if (!exists("dir")) dir = 'bench/out'
set datafile separator ','
set terminal pngcairo size 900,600 font 'sans,10'
set grid
set key top left

# Time against objects, lights, bounce depth and resolution: GPU path and CPU reference.
scaling(name) = sprintf('%s/scaling_%s.csv', dir, name)

set output dir.'/scaling_objects.png'
set title 'Time against objects (many\_spheres: N spheres of six materials and a wall)'
set xlabel 'spheres'; set ylabel 'ms per frame (median)'
set logscale xy 2
plot scaling('objects') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
     '' using 1:6 with linespoints title 'CPU reference'
unset logscale

set output dir.'/scaling_lights.png'
set title 'Time against lights (many\_lights)'
set xlabel 'point lights'
plot scaling('lights') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
     '' using 1:6 with linespoints title 'CPU reference'

set output dir.'/scaling_depth.png'
set title 'Time against bounce depth (glass: mirror and glass spheres)'
set xlabel 'max\_depth (bounce levels)'
set logscale y
plot scaling('depth') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
     '' using 1:6 with linespoints title 'CPU reference'
unset logscale

set output dir.'/scaling_resolution.png'
set title 'Time against resolution (paper\_earth\_shadow)'
set xlabel 'image side (pixels)'
set logscale xy 2
plot scaling('resolution') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
     '' using 1:6 with linespoints title 'CPU reference'
unset logscale

# Time against error: one panel per scene, each trade-off variant a labelled point. Columns of
# tradeoffs.csv: 1 scene, 2 variant, 7 time ratio against the baseline, 14 mean absolute error.
set output dir.'/time_vs_error.png'
set terminal pngcairo size 1400,500 font 'sans,9'
set multiplot layout 1,3 title 'Run time against error of each trade-off (mean absolute error against the CPU reference, 0..255 units)'
set xlabel 'time / baseline time'
set ylabel 'mean absolute error'
set logscale y
set key off
scenes = 'paper_earth_shadow glass textured_aniso'
do for [s in scenes] {
    set title s noenhanced
    plot dir.'/tradeoffs.csv' using (strcol(1) eq s ? $7 : 1/0):($14 > 0 ? $14 : 1e-5) with points pt 7, \
         '' using (strcol(1) eq s ? $7 : 1/0):($14 > 0 ? $14 : 1e-5):2 with labels font ',7' offset 0,0.6 noenhanced
}
unset multiplot
