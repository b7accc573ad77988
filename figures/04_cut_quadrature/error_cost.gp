# Koschier's Table 1 again, as a chart: the largest relative error of the four test polynomials
# against the points a rule uses (top) and its seconds per element (bottom), per cut. cost.csv.
# Errors below 1e-16 are drawn at 1e-16 (round-off: the rule is exact).
set terminal pngcairo size 1500,900 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "error_cost.png"
at_least(e) = e < 1e-16 ? 1e-16 : e
# cost.csv rows of one cut and rule; the sphere's errors are against the tessellated polyhedron (column 9).
pick(cut, rule, c) = (strcol(1) eq cut && strcol(3) eq rule) ? column(c) : NaN
err(cut) = at_least(cut eq "spherical" ? column(9) : column(8))
set style line 1 lc rgb "#d62728" pt 7 ps 1.4           # exact
set style line 2 lc rgb "#9467bd" pt 5 ps 1.2           # Koschier's moment fitting
set style line 3 lc rgb "#2ca02c" pt 9 ps 1.4           # subtets
set style line 4 lc rgb "#7f7f7f" pt 13 ps 1.4          # volume ratio
set style line 5 lc rgb "#1f77b4" pt 6 ps 1.0 lw 1.5    # lattice
set style line 6 lc rgb "#ff7f0e" pt 4 ps 1.0 lw 1.5    # regular
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set yrange [5e-17:20]
set multiplot layout 2,3 title "Koschier Table 1 again: the unit tet's corner piece; largest relative error of 1, x+y+z, yz+xz+xy, x^2+y^2+z^2" font ",13"
do for [row = 1:2] {
  do for [cut in "planar kinked spherical"] {
    set title cut.(cut eq "spherical" ? " (levels 1-6; error vs the tessellated polyhedron = sub-tets)" : "")
    set xlabel (row == 1 ? "quadrature points (nonzero weight)" : "seconds per element (building the rule and summing; one core)")
    set ylabel "largest relative error"
    set key left center box opaque font ",9"  # the middle of the y range is empty: exact rules lie below, the rest above
    xcol = (row == 1 ? 6 : 7)
    plot "cost.csv" using (pick(cut, "exact", xcol)):(err(cut)) w p ls 1 t "exact (24 pts, exact moments)", \
         "" using (pick(cut, "moment_fitting", xcol)):(err(cut)) w p ls 2 t "Koschier moment fitting (24 pts)", \
         "" using (pick(cut, "subtets", xcol)):(err(cut)) w p ls 3 t "sub-tets, 4-pt Gauss", \
         "" using (pick(cut, "volume_ratio", xcol)):(err(cut)) w p ls 4 t "volume ratio", \
         "" using (pick(cut, "lattice", xcol)):(err(cut)) w p ls 5 t "lattice n^3 (Paulus)", \
         "" using (pick(cut, "regular", xcol)):(err(cut)) w p ls 6 t "regular n^3 (Kaufmann)"
  }
}
unset multiplot
