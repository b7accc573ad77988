# Shared look of chapter 2's figures: PNG via cairo, comma-separated data with a header row.
set terminal pngcairo size 1100,480 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
# Rows kept only where column 1 (element) and column 2 (axis) match: ghost.csv.
pick(element, axis, column) = (strcol(1) eq element && strcol(2) eq axis) ? column(column) : NaN
set style line 1 lc rgb "#1f77b4" pt 7 ps 1.0 lw 2          # linear FEM
set style line 2 lc rgb "#1f77b4" pt 6 ps 1.0 lw 2 dt 2
set style line 3 lc rgb "#d62728" pt 5 ps 1.0 lw 2          # corotated Tet10
set style line 4 lc rgb "#d62728" pt 4 ps 1.0 lw 2 dt 2
set style line 5 lc rgb "#ff7f0e" pt 9 ps 1.0 lw 2          # corotated Tet4
set style line 6 lc rgb "#2ca02c" pt 13 ps 1.2 lw 2         # CalculiX NLGEOM
set style line 7 lc rgb "#000000" pt 0 lw 1.5 dt 4          # elastica
set style line 9 lc rgb "#777777" lw 1 dt 3                 # guides
