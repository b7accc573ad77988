# Shared look of chapter 1's figures: PNG via cairo, log axes with powers of ten.
set terminal pngcairo size 1100,520 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set key autotitle columnhead
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set format y "10^{%L}"
# Rows of a CSV column, kept only where column 1 (element) and 2 (load) match.
pick(element, load, column) = (strcol(1) eq element && strcol(2) eq load) ? column(column) : NaN
set style line 1 lc rgb "#1f77b4" pt 7 ps 1.2 lw 2          # Tet4, gravity
set style line 2 lc rgb "#1f77b4" pt 6 ps 1.2 lw 2 dt 2     # Tet4, traction
set style line 3 lc rgb "#d62728" pt 5 ps 1.2 lw 2          # Tet10, gravity
set style line 4 lc rgb "#d62728" pt 4 ps 1.2 lw 2 dt 2     # Tet10, traction
set style line 9 lc rgb "#777777" lw 1 dt 3                 # slope guides
