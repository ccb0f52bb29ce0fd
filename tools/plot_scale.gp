# The scale plot of bench/README.md from the CSV of tools/scale_runs:
#   tools/scale_runs build DIR > scale.csv
#   gnuplot -e "csv='scale.csv'; out='docs/scale.png'" tools/plot_scale.gp
# Log-log: BVH build seconds, peak resident MB, final tables + BVH MB and render Mrays/s
# against triangles.
set datafile separator ','
set terminal pngcairo size 900,600 font ',11'
set output out
set logscale xy
set grid
set key top left
set xlabel 'triangles'
set ylabel 'build s  |  MB  |  Mrays/s'
set title 'raylane: displaced icosphere, import + BVH + path-traced render (640x480, 4 spp)'
plot csv skip 1 using 1:2 with linespoints title 'BVH build (s)', \
     csv skip 1 using 1:4 with linespoints title 'peak resident (MB)', \
     csv skip 1 using 1:5 with linespoints title 'tables + BVH (MB)', \
     csv skip 1 using 1:3 with linespoints title 'render (Mrays/s)'
