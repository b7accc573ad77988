# Koschier Figs. 11 and 12, XFEM against element duplication (examples/06_cut_dynamics_study.cpp,
# parts slab and unfold): two charts.
# slab_drop.png  from slab.csv: the slab cut into five slices, each slice's centre-of-mass drop at
#                rest against its thickness, XFEM, duplication, Euler-Bernoulli's 0.6 rho g L^4 / (E t^2);
# unfold_com.png from unfold_history.csv: the unfolding block on its hinge, the true centre of mass's
#                horizontal distance from the hinge over time (linear and log), XFEM and duplication.
set terminal pngcairo size 1000,650 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key box opaque

set output "slab_drop.png"
set title "Koschier Fig. 11: a slab 61 x 1 x 11 blocks of 1 cm on a wall, cut into five slices; each slice at rest"
set xlabel "slice thickness t (mm)"
set ylabel "drop of the slice's centre of mass at rest (m)"
set logscale xy
set format y "10^{%L}"
set xrange [9:40]
set key top right
plot "slab.csv" using ($3*1e3):(strcol(1) eq "xfem" ? $6 : NaN) w lp pt 7 ps 1.6 lc rgb "#1f77b4" t "XFEM (pieces integrated exactly)", \
     "" using ($3*1e3):(strcol(1) eq "duplication" ? $6 : NaN) w lp pt 5 ps 1.6 lc rgb "#d62728" t "element duplication (a full element per piece)", \
     "" using ($3*1e3):(strcol(1) eq "xfem" ? $7 : NaN) w l dt 2 lc rgb "#555555" t "Euler-Bernoulli cantilever, 0.6 rho g L^4 / (E t^2)"
unset logscale
unset xrange
set format y "%g"

set output "unfold_com.png"
set terminal pngcairo size 1000,900
set multiplot layout 2,1 title "Koschier Fig. 12: a block on a hinge cut into a zig-zag that unfolds (E = 100 kPa, Rayleigh alpha = 2 1/s)"
unset title
set xlabel "t (s)"
set ylabel "true centre of mass: x from the hinge (m)"
set key top right
plot "unfold_history.csv" using 3:(strcol(1) eq "xfem" ? $4 : NaN) w l lc rgb "#1f77b4" t "XFEM", \
     "" using 3:(strcol(1) eq "duplication" ? $4 : NaN) w l lc rgb "#d62728" t "element duplication"
set logscale y
set format y "10^{%L}"
set ylabel "|x from the hinge| (m)"
plot "unfold_history.csv" using 3:(strcol(1) eq "xfem" ? abs($4) : NaN) w l lc rgb "#1f77b4" t "XFEM", \
     "" using 3:(strcol(1) eq "duplication" ? abs($4) : NaN) w l lc rgb "#d62728" t "element duplication"
unset multiplot
