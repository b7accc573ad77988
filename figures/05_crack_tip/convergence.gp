# Chapter 5's convergence study (examples/05_convergence_study.cpp, convergence.csv): Williams's
# mode-I field on the boundary of the cracked slab. Left: the relative L2 error against the cell
# size h for no branch functions, topological and geometric (r_e = 0.1 m) enrichment, the last two also
# with Fries's blending correction, Tet4 (lines) and Tet10 (open points). Middle: the relative energy error. Right: the geometric
# radius against cost on n = 9 and 17 (relative L2 error against unknowns).
set terminal pngcairo size 1650,560 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "convergence.png"
# column 1 part, 2 enrichment, 3 order, 4 boundary, 6 h, 7 radius_rule, 11 unknowns,
# 15/16 L2 and its scale, 17/18 energy and its scale
pick(part, e, order) = (strcol(1) eq part && strcol(2) eq e && column(3) == order && strcol(4) eq "interpolated") ? column(6) : NaN
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "cell size h (m)"
set key bottom right box opaque font ",9"
set multiplot layout 1,3 title "Williams mode I on the boundary of a cracked slab, front through the middle of elements" font ",13"
set title "relative L2 error"
set ylabel "||u_h - u|| / ||u||"
plot "convergence.csv" using (pick("ladder", "none", 1)):($15/$16) w lp pt 9 lc rgb "#2ca02c" t "none (Heaviside only), Tet4", \
     "" using (pick("ladder", "topological", 1)):($15/$16) w lp pt 5 lc rgb "#1f77b4" t "topological, Tet4", \
     "" using (pick("ladder", "geometric", 1)):($15/$16) w lp pt 7 lc rgb "#d62728" t "geometric r_e = 0.1 m, Tet4", \
     "" using (pick("corrected", "topological", 1)):($15/$16) w lp pt 13 lc rgb "#17becf" t "topological, Fries-corrected, Tet4", \
     "" using (pick("corrected", "geometric", 1)):($15/$16) w lp pt 11 lc rgb "#9467bd" t "geometric, Fries-corrected, Tet4", \
     "" using (pick("tet10", "none", 2)):($15/$16) w lp pt 8 dt 2 lc rgb "#2ca02c" t "none, Tet10", \
     "" using (pick("tet10", "topological", 2)):($15/$16) w lp pt 4 dt 2 lc rgb "#1f77b4" t "topological, Tet10", \
     "" using (pick("tet10", "geometric", 2)):($15/$16) w lp pt 6 dt 2 lc rgb "#d62728" t "geometric, Tet10", \
     [0.02:0.25] 2.0*x**2 dt 3 lc rgb "#777777" t "h^2", [0.02:0.25] 0.45*x dt 4 lc rgb "#777777" t "h"
set title "relative energy error"
set ylabel "||u_h - u||_E / ||u||_E"
plot "convergence.csv" using (pick("ladder", "none", 1)):($17/$18) w lp pt 9 lc rgb "#2ca02c" t "none, Tet4", \
     "" using (pick("ladder", "topological", 1)):($17/$18) w lp pt 5 lc rgb "#1f77b4" t "topological, Tet4", \
     "" using (pick("ladder", "geometric", 1)):($17/$18) w lp pt 7 lc rgb "#d62728" t "geometric, Tet4", \
     "" using (pick("corrected", "topological", 1)):($17/$18) w lp pt 13 lc rgb "#17becf" t "topological, corrected, Tet4", \
     "" using (pick("corrected", "geometric", 1)):($17/$18) w lp pt 11 lc rgb "#9467bd" t "geometric, corrected, Tet4", \
     "" using (pick("tet10", "none", 2)):($17/$18) w lp pt 8 dt 2 lc rgb "#2ca02c" t "none, Tet10", \
     "" using (pick("tet10", "topological", 2)):($17/$18) w lp pt 4 dt 2 lc rgb "#1f77b4" t "topological, Tet10", \
     "" using (pick("tet10", "geometric", 2)):($17/$18) w lp pt 6 dt 2 lc rgb "#d62728" t "geometric, Tet10", \
     [0.02:0.25] 5.0*x dt 3 lc rgb "#777777" t "h", [0.02:0.25] 2.5*x**0.5 dt 4 lc rgb "#777777" t "h^{1/2}"
set title "geometric radius against cost (n = 9, 17)"
set xlabel "unknowns"
set ylabel "||u_h - u|| / ||u||"
radius(rule) = (strcol(1) eq "radius" && strcol(7) eq rule) ? column(11) : NaN
plot for [rule in "0 h 2h 4h 0.05m 0.1m 0.2m default"] "convergence.csv" using (radius(rule)):($15/$16) w lp t "r_e = ".(rule eq "0" ? "0 (topological)" : rule)
unset multiplot
