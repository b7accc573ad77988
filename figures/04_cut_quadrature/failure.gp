# Where chapter 4's pieces fail (examples/04_failure_study.cpp), two charts:
# failure_fraction.png from failure_fraction.csv: the cut a distance d above a node layer, every
# rule, Tet4 (top) and Tet10 (bottom): condition number of K_ff, plain and Jacobi-scaled, and the
# difference from the cut on the layer; points without the guard, crosses with eq. 22 at
# Koschier's 1e-9 (Kerf's default), stars with chapter 3's 1e-4.
# failure_kink.png from failure_kink.csv: the fraction of points near a kink that each sign test
# puts on the wrong side, against the angle between the two planes' normals.
set terminal pngcairo size 1500,900 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
# failure_fraction.csv rows of one element, rule and guard (column 5; 0 = off).
pick(el, rule, guard, c) = (strcol(1) eq el && strcol(4) eq rule && column(5) == guard) ? column(c) : NaN
floor16(e) = e < 1e-16 ? 1e-16 : e
set style line 1 lc rgb "#d62728" pt 7 ps 1.2 lw 1.5    # exact
set style line 2 lc rgb "#9467bd" pt 5 ps 1.1 lw 1.5    # Koschier's moment fitting
set style line 3 lc rgb "#2ca02c" pt 9 ps 1.3 lw 1.5    # subtets
set style line 4 lc rgb "#7f7f7f" pt 13 ps 1.3 lw 1.5   # volume ratio
set style line 5 lc rgb "#1f77b4" pt 6 ps 1.1 lw 1.5    # lattice

set output "failure_fraction.png"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [*:*] reverse
set multiplot layout 2,3 title "A sliver: the half-depth cut at z = 0.1 + d, 'pull'; points: every sliver kept; crosses: eq. 22 at its default 10^{-9}; stars: at 10^{-4}" font ",13"
do for [el in "tet4 tet10"] {
  do for [panel = 1:3] {
    c = panel == 1 ? 15 : (panel == 2 ? 16 : 17)
    set title (el eq "tet4" ? "Tet4, 4x4x10 cells: " : "Tet10, 2x2x6 cells: ").(panel == 1 ? "cond K_{ff}" : (panel == 2 ? "cond D^{-1/2} K_{ff} D^{-1/2}" : "difference from the cut on the layer"))
    set xlabel "d / h"
    set ylabel (panel == 3 ? "relative L2 difference (outside the slab)" : "condition number (dense eigenvalues)")
    if (panel == 3) { set key top right box opaque font ",8"; set yrange [1e-16:10] } else { set key top left box opaque font ",8"; set yrange [1:1e20] }
    plot "failure_fraction.csv" using (pick(el, "subtets", 0, 3)):(floor16(pick(el, "subtets", 0, c))) w p ls 3 t "subtets", \
         "" using (pick(el, "exact", 0, 3)):(floor16(pick(el, "exact", 0, c))) w p ls 1 t "exact", \
         "" using (pick(el, "moment_fitting", 0, 3)):(floor16(pick(el, "moment_fitting", 0, c))) w p ls 2 t "moment\\_fitting", \
         "" using (pick(el, "lattice", 0, 3)):(floor16(pick(el, "lattice", 0, c))) w p ls 5 t "lattice (n = 5)", \
         "" using (pick(el, "volume_ratio", 0, 3)):(floor16(pick(el, "volume_ratio", 0, c))) w p ls 4 t (el eq "tet4" ? "volume\\_ratio" : ""), \
         "" using (pick(el, "subtets", 1e-9, 3)):(floor16(pick(el, "subtets", 1e-9, c))) w p ls 3 pt 1 ps 1.8 notitle, \
         "" using (pick(el, "subtets", 1e-4, 3)):(floor16(pick(el, "subtets", 1e-4, c))) w p ls 3 pt 3 ps 1.4 notitle, \
         "" using (pick(el, "exact", 1e-9, 3)):(floor16(pick(el, "exact", 1e-9, c))) w p ls 1 pt 1 ps 1.8 notitle, \
         "" using (pick(el, "exact", 1e-4, 3)):(floor16(pick(el, "exact", 1e-4, c))) w p ls 1 pt 3 ps 1.4 notitle, \
         "" using (pick(el, "moment_fitting", 1e-9, 3)):(floor16(pick(el, "moment_fitting", 1e-9, c))) w p ls 2 pt 1 ps 1.8 notitle, \
         "" using (pick(el, "moment_fitting", 1e-4, 3)):(floor16(pick(el, "moment_fitting", 1e-4, c))) w p ls 2 pt 3 ps 1.4 notitle, \
         "" using (pick(el, "lattice", 1e-9, 3)):(floor16(pick(el, "lattice", 1e-9, c))) w p ls 5 pt 1 ps 1.8 notitle, \
         "" using (pick(el, "lattice", 1e-4, 3)):(floor16(pick(el, "lattice", 1e-4, c))) w p ls 5 pt 3 ps 1.4 notitle, \
         "" using (pick(el, "volume_ratio", 1e-9, 3)):(floor16(pick(el, "volume_ratio", 1e-9, c))) w p ls 4 pt 1 ps 1.8 notitle, \
         "" using (pick(el, "volume_ratio", 1e-4, 3)):(floor16(pick(el, "volume_ratio", 1e-4, c))) w p ls 4 pt 3 ps 1.4 notitle
  }
}
unset multiplot

set output "failure_kink.png"
set terminal pngcairo size 1000,620 enhanced font "DejaVu Sans,11" linewidth 1.5
unset logscale
set format x "%g"
set format y "%g"
set xrange [0:160] noreverse
set yrange [-0.02:*]
set title "The side of a point within 0.1 of a kink's line, against the pieces that hold it" noenhanced
set xlabel "angle between the two planes' normals (degrees; 90: a right-angled fold)"
set ylabel "fraction of points on the wrong side"
set key top left box opaque
set arrow 1 from 90, graph 0 to 90, graph 1 nohead lc rgb "#777777" dt 3
kink(surface, c) = strcol(1) eq surface ? column(c) : NaN
plot "failure_kink.csv" using (kink("ridge", 3)):(kink("ridge", 8)) w lp ls 1 t "closest triangle (Paulus), ridges z = 0.55 - s|x - 0.5|", \
     "" using (kink("valley", 3)):(kink("valley", 8)) w lp ls 5 t "closest triangle, valleys z = 0.45 + s|x - 0.5|", \
     "" using (kink("table1", 3)):(kink("table1", 8)) w p ls 2 ps 2 t "closest triangle, Table 1's kinked cut of the unit tet", \
     "" using (kink("ridge", 3)):(kink("ridge", 9)) w lp ls 3 t "angle-weighted pseudo-normal, ridges", \
     "" using (kink("valley", 3)):(kink("valley", 9)) w lp ls 4 t "angle-weighted pseudo-normal, valleys"
