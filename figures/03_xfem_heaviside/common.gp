# Shared look of chapter 3's figures: PNG via cairo, comma-separated data with a header row.
set terminal pngcairo size 1200,720 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
# ladder.csv rows kept only where case, model and method match.
pick(case, model, method, column) = (strcol(1) eq case && strcol(2) eq model && strcol(3) eq method) ? column(column) : NaN
# fraction.csv rows kept only where the front placement and the rule match (rule 0 = off).
pickf(front, rule, column) = (strcol(1) eq front && column(4) == rule) ? column(column) : NaN
set style line 1 lc rgb "#d62728" pt 7 ps 1.0 lw 2          # XFEM Tet4
set style line 2 lc rgb "#1f77b4" pt 5 ps 1.0 lw 2          # conforming Tet4
set style line 3 lc rgb "#2ca02c" pt 9 ps 1.2 lw 2          # conforming Tet10
set style line 4 lc rgb "#ff7f0e" pt 6 ps 1.0 lw 2 dt 2
set style line 9 lc rgb "#777777" lw 1 dt 3                 # guides
