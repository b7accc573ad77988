# Where crack-tip enrichment fails: the 2-norm condition number of the static stiffness K_ff
# with the branch DOFs, bare and with four cures (Jacobi scaling, Koschier's bilateral
# diagonal, the part basis then Jacobi, Bechet's node blocks), against the geometric enrichment
# radius (top left) and against the front's distance d to a node (top right: the node ahead of
# the front; bottom left: behind it, the cut passing d/2 from it) and to a plane of faces
# (bottom right). failures.csv, written by examples/05_failure_study.cpp.
set terminal pngcairo size 1400,1000 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "failures.png"
pick(series, x) = strcol(1) eq series ? column(x) : NaN
set logscale y
set format y "10^{%L}"
set ylabel "condition number of K_{ff}"
set multiplot layout 2,2 title "Chapter 5: conditioning of the static stiffness with branch DOFs (Tet4, bottom clamped)" font ",13"

set title "geometric enrichment radius (9 x 9 x 2 cells)"
set xlabel "r_e / h (0: topological)"
set key top left box opaque font ",9"
plot "failures.csv" using (pick("radius", 2)):8 w lp pt 7 lc rgb "#000000" t "bare", \
     "" using (pick("radius", 2)):9 w lp pt 5 lc rgb "#1f77b4" t "Jacobi", \
     "" using (pick("radius", 2)):10 w lp pt 9 lc rgb "#ff7f0e" t "Koschier eqs. 23-27", \
     "" using (pick("radius", 2)):11 w lp pt 11 lc rgb "#2ca02c" t "part basis + Jacobi", \
     "" using (pick("radius", 2)):12 w lp pt 13 lc rgb "#d62728" t "node blocks (Bechet)"

set logscale x
set format x "10^{%L}"
set xlabel "d / h"
set xrange [5e-4:0.2] reverse
do for [s in "node_ahead node_behind"] {
  set title (s eq "node_ahead" ? "front nearing a node (node ahead, 60 deg)" : "front nearing a node (node behind, 150 deg)")
  unset key
  plot "failures.csv" using (pick(s, 3)):8 w lp pt 7 lc rgb "#000000" t "bare", \
       "" using (pick(s, 3)):9 w lp pt 5 lc rgb "#1f77b4" t "Jacobi", \
       "" using (pick(s, 3)):10 w lp pt 9 lc rgb "#ff7f0e" t "Koschier eqs. 23-27", \
       "" using (pick(s, 3)):11 w lp pt 11 lc rgb "#2ca02c" t "part basis + Jacobi", \
       "" using (pick(s, 3)):12 w lp pt 13 lc rgb "#d62728" t "node blocks (Bechet)"
}
set title "front nearing a plane of faces (solid: before it, dashed: just past it)"
plot "failures.csv" using (pick("face_before", 3)):8 w lp pt 7 lc rgb "#000000" t "bare", \
     "" using (pick("face_before", 3)):9 w lp pt 5 lc rgb "#1f77b4" t "Jacobi", \
     "" using (pick("face_before", 3)):12 w lp pt 13 lc rgb "#d62728" t "node blocks", \
     "" using (pick("face_after", 3)):8 w lp pt 6 dt 2 lc rgb "#000000" notitle, \
     "" using (pick("face_after", 3)):9 w lp pt 4 dt 2 lc rgb "#1f77b4" notitle, \
     "" using (pick("face_after", 3)):12 w lp pt 12 dt 2 lc rgb "#d62728" notitle
unset multiplot
