# gnuplot scripts/plot_equal_error.gp (from the repository root): docs/images/speed_error_vs_time_cornell_512.png
# from docs/data/speed_equal_error_cornell_512.csv (scripts/measure_equal_error.sh).
set terminal pngcairo size 800,520 font "DejaVu Sans,11"
set output "docs/images/speed_error_vs_time_cornell_512.png"
set datafile separator ","
set logscale xy
set xlabel "seconds (load + walk + raster (+ compensation), or path tracing)"
set ylabel "relMSE against pt 4096 spp"
set title "Cornell box 512x512, llvmpipe, LP_NUM_THREADS=2, 2 shared cores" noenhanced
set key top right
set grid
set format y "%.0e"
f(x) = 0.000697
plot \
  "< grep '^pt,' docs/data/speed_equal_error_cornell_512.csv" using 4:5 with linespoints lw 2 pt 7 title "pt (4, 16, 64, 256 spp)", \
  "< grep '^raster,k=4,' docs/data/speed_equal_error_cornell_512.csv" using 4:5 with linespoints lw 2 pt 5 title "raster k=4, batch 16 (N = 64 .. 16384)", \
  "< grep '^raster,k=4 batch=1,' docs/data/speed_equal_error_cornell_512.csv" using 4:5 with linespoints lw 1 pt 4 dt 2 title "raster k=4, batch 1 (the same images)", \
  "< grep '^raster,k=4 bias' docs/data/speed_equal_error_cornell_512.csv" using 4:5 with linespoints lw 2 pt 9 title "raster k=4, --bias-compensation (N = 64 .. 4096)", \
  f(x) with lines dt 3 lc rgb "gray" title "pt's relMSE at 60 s (7.0e-4)"
