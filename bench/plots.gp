# Plots of a benchmark run: gnuplot -e "dir='bench/out'" bench/plots.gp
# Reads the CSV files the bench programs wrote into dir and writes PNG files beside them; a plot whose
# CSV is not there (its program not run, or BENCH_CASES left its cases out) is passed over with a line
# on stderr, so that a partial run still gets the plots of what it ran.
if (!exists("dir")) dir = 'bench/out'
have(file) = system(sprintf("test -f '%s' && echo yes || echo no", file)) eq 'yes'
set datafile separator ','
set terminal pngcairo size 900,600 font 'sans,10' noenhanced
set grid
set key top left

# Time against objects, lights, bounce depth and resolution: GPU path and CPU reference.
scaling(name) = sprintf('%s/scaling_%s.csv', dir, name)

if (!have(scaling('objects'))) {
    print 'no scaling_objects.csv: no scaling_objects.png'
} else {
    set output dir.'/scaling_objects.png'
    set title 'Time against objects (many_spheres: N spheres of six materials and a wall)'
    set xlabel 'spheres'; set ylabel 'ms per frame (median)'
    set logscale xy 2
    plot scaling('objects') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
         '' using 1:6 with linespoints title 'CPU reference'
    unset logscale
}

if (!have(scaling('lights'))) {
    print 'no scaling_lights.csv: no scaling_lights.png'
} else {
    set output dir.'/scaling_lights.png'
    set title 'Time against lights (many_lights)'
    set xlabel 'point lights'
    plot scaling('lights') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
         '' using 1:6 with linespoints title 'CPU reference'
}

if (!have(scaling('depth'))) {
    print 'no scaling_depth.csv: no scaling_depth.png'
} else {
    set output dir.'/scaling_depth.png'
    set title 'Time against bounce depth (glass: mirror and glass spheres)'
    set xlabel 'max_depth (bounce levels)'
    set logscale y
    plot scaling('depth') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
         '' using 1:6 with linespoints title 'CPU reference'
    unset logscale
}

if (!have(scaling('resolution'))) {
    print 'no scaling_resolution.csv: no scaling_resolution.png'
} else {
    set output dir.'/scaling_resolution.png'
    set title 'Time against resolution (paper_earth_shadow)'
    set xlabel 'image side (pixels)'
    set logscale xy 2
    plot scaling('resolution') using 1:3:4:5 with yerrorlines title 'GPU path (min-max bars)', \
         '' using 1:6 with linespoints title 'CPU reference'
    unset logscale
}

# Time against error: one panel per scene, a labelled point per precision trade-off (depth format,
# G-buffer format, dmax) and the baseline. Columns of tradeoffs.csv: 1 scene, 2 variant, 7 time ratio
# against the baseline, 14 mean absolute error.
scenes = 'paper_earth_shadow glass textured_aniso'
precision(v) = (v eq 'baseline' || v eq 'float_depth_32' || v eq 'gbuffer_rgba16f' || v eq 'dmax_x10' || v eq 'dmax_x1000')
if (!have(dir.'/tradeoffs.csv')) {
    print 'no tradeoffs.csv: no time_vs_error.png or skips.png'
} else {
    set output dir.'/time_vs_error.png'
    set terminal pngcairo size 1400,500 font 'sans,9' noenhanced
    set multiplot layout 1,3 title 'Run time against error of the precision trade-offs (mean absolute error against the CPU reference, 0..255 units)'
    set xlabel 'time / baseline time'
    set ylabel 'mean absolute error (log)'
    set logscale y
    set key off
    set offsets graph 0.05, graph 0.3, graph 0.1, graph 0.1
    set format y '%g'
    do for [s in scenes] {
        set title s noenhanced
        plot dir.'/tradeoffs.csv' using ((strcol(1) eq s && precision(strcol(2))) ? $7 : 1/0):($14 > 0 ? $14 : 1e-5) with points pt 7 ps 1.2, \
             '' using ((strcol(1) eq s && precision(strcol(2))) ? $7 : 1/0):($14 > 0 ? $14 : 1e-5):2 with labels font ',8' rotate by 30 left offset 0.5,0.4 noenhanced
    }
    unset multiplot
    unset logscale
    set offsets 0, 0, 0, 0
    set format y '% h'

    # What each skip saves: time with the skip switched off, against the baseline (bars clipped at 4x,
    # the value printed). Every skip leaves the image bit-identical (pixels_changed, column 8).
    set output dir.'/skips.png'
    set terminal pngcairo size 1400,500 font 'sans,9' noenhanced
    set multiplot layout 1,3 title 'Time with one skip switched off, relative to the baseline (1 = no saving); images are identical'
    set xlabel 'time / baseline time'
    set ylabel ''
    set xrange [0:4.6]
    set style fill solid 0.6
    set arrow 1 from 1, graph 0 to 1, graph 1 nohead dashtype 2
    skip(v) = (v[1:3] eq 'no_')
    do for [s in scenes] {
        set title s noenhanced
        plot dir.'/tradeoffs.csv' using ((strcol(1) eq s && skip(strcol(2))) ? ($7 < 4 ? $7 : 4) / 2 : 1/0):0:((($7 < 4) ? $7 : 4) / 2):(0.35):ytic(2) with boxxyerror, \
             '' using ((strcol(1) eq s && skip(strcol(2))) ? ($7 < 4 ? $7 : 4) + 0.05 : 1/0):0:(sprintf('%.2f', $7)) with labels left font ',8'
    }
    unset multiplot
    unset arrow 1
}

# Distribution ray tracing (bench_distribution): RMSE against samples per pixel, one colour per scene,
# the GPU's as lines and the CPU reference's as open circles (the same sample points, so they fall on
# the lines), beside a line of slope -1/2, plain Monte Carlo noise, through the largest 1-sample error.
# The scenes come from the CSV's first column, so a scene added to the program needs no line here.
# Columns of distribution_error.csv: 1 scene, 2 size, 3 samples, 4 GPU RMSE, 5 CPU RMSE, 8 reference samples.
distribution = dir.'/distribution_error.csv'
if (!have(distribution)) {
    print 'no distribution_error.csv: no distribution_error.png'
} else {
    # stats honours the ranges, so the skips plot's xrange must go first.
    set xrange [*:*]
    set yrange [*:*]
    dscenes = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | uniq | tr '\\n' ' '", distribution))
    stats distribution using ($3 == 1 ? $4 : 1/0) nooutput
    anchor = STATS_max
    stats distribution using 2:8 nooutput
    set output dir.'/distribution_error.png'
    set terminal pngcairo size 900,600 font 'sans,10' noenhanced
    set title sprintf('RMSE against samples per pixel at %.0fx%.0f (linear radiance, against a CPU reference of %.0f samples)', \
                     STATS_max_x, STATS_max_x, STATS_max_y)
    set xlabel 'samples per pixel'
    set ylabel 'RMSE'
    set style fill empty
    set logscale x 2
    set logscale y
    set format y '%g'
    set key top right
    plot for [i=1:words(dscenes)] distribution using (strcol(1) eq word(dscenes, i) ? $3 : 1/0):4 \
             with linespoints lc i pt 7 title word(dscenes, i).' (GPU)', \
         for [i=1:words(dscenes)] '' using (strcol(1) eq word(dscenes, i) ? $3 : 1/0):5 with points lc i pt 6 ps 1.6 \
             title word(dscenes, i).' (CPU reference)', \
         anchor / sqrt(x) with lines dt 2 lc 'black' title 'slope -1/2'
    unset logscale
    set format y '% h'
}

# The path integrator (bench_path): RMSE against samples per pixel on the Cornell box files, one colour
# per scene: over the pixels away from the light (solid, the path noise) and over all pixels (dashed:
# the light's edge, at radiance 17 against walls below 1, adds the pixel pattern's coverage error),
# the CPU reference's as lines and the GPU's as open circles where a GPU plan draws the path integrator
# (an empty column otherwise, which gnuplot skips), beside a line of slope -1/2 through the largest
# 1-sample error away from the light. Columns of path_error.csv: 1 scene, 2 size, 3 samples, 4 CPU
# RMSE, 5 GPU RMSE, 8 reference samples, 10 CPU RMSE away from the light, 11 GPU RMSE away.
path_error = dir.'/path_error.csv'
if (!have(path_error)) {
    print 'no path_error.csv: no path_error.png'
} else {
    set xrange [*:*]
    set yrange [*:*]
    pscenes = system(sprintf("tail -n +2 '%s' | cut -d, -f1 | uniq | tr '\\n' ' '", path_error))
    stats path_error using ($3 == 1 ? $10 : 1/0) nooutput
    anchor = STATS_max
    stats path_error using 2:8 nooutput
    set output dir.'/path_error.png'
    set terminal pngcairo size 900,600 font 'sans,10' noenhanced
    set title sprintf('Path integrator: RMSE against samples per pixel at %.0fx%.0f (linear radiance, against a CPU reference of %.0f samples)', \
                     STATS_max_x, STATS_max_x, STATS_max_y)
    set xlabel 'samples per pixel'
    set ylabel 'RMSE'
    set logscale x 2
    set logscale y
    set format y '%g'
    set key bottom left
    plot for [i=1:words(pscenes)] path_error using (strcol(1) eq word(pscenes, i) ? $3 : 1/0):10 \
             with linespoints lc i pt 7 title word(pscenes, i).', away from the light (CPU reference)', \
         for [i=1:words(pscenes)] '' using (strcol(1) eq word(pscenes, i) ? $3 : 1/0):4 \
             with linespoints lc i dt 2 pt 1 title word(pscenes, i).', all pixels (CPU reference)', \
         for [i=1:words(pscenes)] '' using (strcol(1) eq word(pscenes, i) ? $3 : 1/0):11 with points lc i pt 6 ps 1.6 \
             title word(pscenes, i).', away from the light (GPU)', \
         anchor / sqrt(x) with lines dt 3 lc 'black' title 'slope -1/2'
    unset logscale
    set format y '% h'
}

# Time against triangle count (bench_mesh's closed series): the GPU path (BG_PLAN_AUTO) and the Embree
# peer on icospheres of 5120 to 1310720 triangles, a line per renderer and image size (min-max bars),
# with the 10^6-triangle terrain as lone points. Both axes are logarithmic: equal steps up mean equal
# ratios, so the gap between a GPU line and its Embree line is GPU / Embree. Columns of
# mesh_closed.csv: 1 mesh, 2 triangles, 3 size, 5-7 Embree median, min, max, 8-10 GPU median, min, max.
closed = dir.'/mesh_closed.csv'
if (!have(closed)) {
    print 'no mesh_closed.csv: no mesh_time.png'
} else {
    set output dir.'/mesh_time.png'
    set terminal pngcairo size 900,600 font 'sans,10' noenhanced
    set title 'Time against triangles (closed meshes: icospheres; 2 point lights with shadows, no bounces)'
    set xlabel 'triangles (log)'
    set ylabel 'ms per frame, median (log)'
    set xrange [2000:4e6]
    set yrange [*:*]
    set logscale x 10
    set logscale y
    set format x '%.0s%c'
    set format y '%g'
    set key top left
    sides = system(sprintf("tail -n +2 '%s' | cut -d, -f3 | sort -n | uniq | tr '\\n' ' '", closed))
    # The rows of one mesh kind and size, through awk: a line drawn over rows filtered in gnuplot would
    # break at every row of the other size between them.
    rows(kind, side) = sprintf("< awk -F, '$1 ~ /^%s/ && $3 == %s' '%s'", kind, side, closed)
    plot for [i=1:words(sides)] rows('icosphere', word(sides, i)) using 2:8:9:10 \
             with yerrorlines lc i pt 7 title sprintf('GPU, icosphere, %s^2', word(sides, i)), \
         for [i=1:words(sides)] rows('icosphere', word(sides, i)) using 2:5:6:7 \
             with yerrorlines lc i dt 2 pt 6 title sprintf('Embree, icosphere, %s^2', word(sides, i)), \
         for [i=1:words(sides)] rows('terrain', word(sides, i)) using 2:8 \
             with points lc i pt 5 ps 1.5 title sprintf('GPU, terrain, %s^2', word(sides, i)), \
         for [i=1:words(sides)] rows('terrain', word(sides, i)) using 2:5 \
             with points lc i pt 4 ps 1.5 title sprintf('Embree, terrain, %s^2', word(sides, i))
    unset logscale
    set format x '% h'
    set format y '% h'
}
