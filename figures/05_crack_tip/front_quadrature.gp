# The crack-tip integrands over a tet the front crosses (left) and one it grazes (right): relative
# error against the number of points, per integrand, for sub-tets refined k = 0..4 times with
# Gauss rules of degree 2 and 5, and for the collapsed rule with n = 1..8 points per direction.
# front_quadrature.csv, written by examples/05_front_quadrature_study.cpp. Errors below 1e-16
# are drawn at 1e-16 (round-off).
set terminal pngcairo size 1500,1000 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "front_quadrature.png"
at_least(e) = e < 1e-16 ? 1e-16 : e
pick(tet, rule, f) = (strcol(1) eq tet && strcol(2) eq rule && strcol(4) eq f) ? column(5) : NaN
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set yrange [5e-17:10]
set xlabel "quadrature points"
set ylabel "relative error"
set multiplot layout 2,5 title "Crack-tip integrands over one tet: refined sub-tets (Gauss degree 2, 5) vs the collapsed rule (front\\_quadrature.hpp)" font ",13"
first = 1
do for [tet in "crossed grazing"] {
  do for [f in "1/sqrt(r) 1/r sqrt(r)sin(t/2) cos(t/2)/sqrt(r) sin(3t/2)^2/r"] {
    set title tet.": ".f
    # One legend, in the first panel's empty upper right.
    if (first) { set key top right box opaque font ",8" } else { unset key }
    first = 0
    plot "front_quadrature.csv" using (pick(tet, "subtets_degree2", f)):(at_least(column(8))) w lp pt 9 lc rgb "#2ca02c" t "sub-tets, degree 2, k = 0..4", \
         "" using (pick(tet, "subtets_degree5", f)):(at_least(column(8))) w lp pt 5 lc rgb "#1f77b4" t "sub-tets, degree 5, k = 0..4", \
         "" using (pick(tet, "collapsed", f)):(at_least(column(8))) w lp pt 7 lc rgb "#d62728" t "collapsed, n = 1..8"
  }
}
unset multiplot
