# Chapter 6's validation of the cut body in time (examples/06_cut_dynamics_study.cpp): four charts.
# slice_swing.png     from slice_history.csv: Schoch's falling slice, linear XFEM against
#                     corotational XFEM: the slice's rotation, the stretch of its edges, the energies;
# hinge_offset.png    from hinge.csv: Koschier's hinged cube, the slice's centre of mass at rest
#                     from the hinge, XFEM (consistent, lumped, virtual-tet lumping) and element
#                     duplication, with the geometry's predictions;
# rotations_cost.png  from rotations.csv: frozen rotations against Newton per step, error of the
#                     flap tip against dt and against the milliseconds it cost;
# explicit_blowup.png from explicit.csv: the central difference at 0.9, 1.01, 1.1 dt_crit.
set terminal pngcairo size 1000,650 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key box opaque

set output "slice_swing.png"
set terminal pngcairo size 1000,1000
set multiplot layout 3,1 title "Schoch Fig. 4: a slice hanging by a 5 mm strip swings under gravity (Tet4 3 x 6 x 20, dt = 5 ms, no damping)"
set xlabel "t (s)"
set ylabel "rotation of the slice (deg)"
plot "slice_history.csv" using ($3):(strcol(1) eq "linear" ? $8 : NaN) w l lc rgb "#d62728" t "linear XFEM", \
     "" using ($3):(strcol(1) eq "corotational" ? $8 : NaN) w l lc rgb "#1f77b4" t "corotational XFEM"
set ylabel "|edge stretch| (length / rest length - 1)"
set logscale y
set format y "10^{%L}"
set key bottom right
plot "slice_history.csv" using ($3):(strcol(1) eq "linear" && $2 > 0 ? abs($9) : NaN) w l lc rgb "#d62728" t "linear, top edge", \
     "" using ($3):(strcol(1) eq "linear" && $2 > 0 ? abs($10) : NaN) w l dt 2 lc rgb "#d62728" t "linear, side edge", \
     "" using ($3):(strcol(1) eq "corotational" && $2 > 0 ? abs($9) : NaN) w l lc rgb "#1f77b4" t "corotational, top edge", \
     "" using ($3):(strcol(1) eq "corotational" && $2 > 0 ? abs($10) : NaN) w l dt 2 lc rgb "#1f77b4" t "corotational, side edge"
unset logscale y
set format y "%g"
set ylabel "energy (J)"
set key top left
plot "slice_history.csv" using ($3):(strcol(1) eq "linear" ? $4 : NaN) w l lc rgb "#d62728" t "linear: kinetic", \
     "" using ($3):(strcol(1) eq "linear" ? $5 : NaN) w l dt 2 lc rgb "#d62728" t "linear: elastic", \
     "" using ($3):(strcol(1) eq "corotational" ? $4 : NaN) w l lc rgb "#1f77b4" t "corotational: kinetic", \
     "" using ($3):(strcol(1) eq "corotational" ? $5 : NaN) w l dt 2 lc rgb "#1f77b4" t "corotational: elastic"
unset multiplot

set terminal pngcairo size 1000,650
set output "hinge_offset.png"
set title "Koschier Fig. 10: a five-tet cube hinged on an edge, cut at x = c; the slice [0, c] at rest"
set xlabel "cut position c (m); the slice is [0, c] x [0, 1] x [0, 1]"
set ylabel "slice's centre of mass at rest, x from the hinge (m)"
set key bottom right
set xrange [0.1:0.9]
set yrange [-0.45:0.05]
plot "hinge.csv" using 1:(strcol(2) eq "xfem" ? $4 : NaN) w p pt 7 ps 1.6 lc rgb "#1f77b4" t "XFEM, consistent mass (pieces integrated exactly)", \
     "" using 1:(strcol(2) eq "xfem_lumped" ? $4 : NaN) w p pt 6 ps 2.4 lc rgb "#2ca02c" t "XFEM, default lumped mass (Bernstein: each piece's own first moment)", \
     "" using 1:(strcol(2) eq "xfem_virtual_tet" ? $4 : NaN) w p pt 9 ps 1.6 lc rgb "#ff7f0e" t "XFEM, virtual-tet lumping (each piece's weight at its tet's centroid)", \
     "" using 1:(strcol(2) eq "xfem_virtual_tet" ? $7 : NaN) w l dt 3 lc rgb "#ff7f0e" notitle, \
     "" using 1:(strcol(2) eq "duplication" ? $4 : NaN) w p pt 5 ps 1.6 lc rgb "#d62728" t "element duplication (a full element per piece)", \
     "" using 1:(strcol(2) eq "duplication" ? $7 : NaN) w l dt 2 lc rgb "#555555" t "geometry: the model's centre of weight under the hinge"
unset xrange
unset yrange

set output "rotations_cost.png"
set terminal pngcairo size 1200,550
set multiplot layout 1,2 title "The demo's flap, 0.6 s: frozen rotations (one solve a step) against Newton per step; reference Newton at dt = 0.625 ms"
unset title
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "dt (s)"
set ylabel "largest flap-tip error / largest tip displacement"
set key top left
plot "rotations.csv" using 3:(strcol(1) eq "frozen" ? $9 : NaN) w lp pt 7 lc rgb "#ff7f0e" t "frozen rotations", \
     "" using 3:(strcol(1) eq "newton" ? $9 : NaN) w lp pt 5 lc rgb "#2ca02c" t "Newton to 1e-10"
set xlabel "run time (ms, one core)"
set key top right
plot "rotations.csv" using 6:(strcol(1) eq "frozen" ? $9 : NaN) w lp pt 7 lc rgb "#ff7f0e" t "frozen rotations", \
     "" using 6:(strcol(1) eq "newton" ? $9 : NaN) w lp pt 5 lc rgb "#2ca02c" t "Newton to 1e-10"
unset multiplot
unset logscale x

set terminal pngcairo size 1000,650
set output "explicit_blowup.png"
set title "Central difference on the cut flap (linear XFEM, lumped mass), forced past its critical step"
set xlabel "step"
set ylabel "kinetic + elastic energy (J)"
set format x "%g"
set logscale y
set key top right
plot "explicit.csv" using 2:(($1 == 0.9 && $2 > 0) ? $4 : NaN) w l lc rgb "#1f77b4" t "dt = 0.9 dt_{crit}", \
     "" using 2:(($1 == 1.01 && $2 > 0) ? $4 : NaN) w l lc rgb "#ff7f0e" t "dt = 1.01 dt_{crit}", \
     "" using 2:(($1 == 1.1 && $2 > 0) ? $4 : NaN) w l lc rgb "#d62728" t "dt = 1.1 dt_{crit}"
