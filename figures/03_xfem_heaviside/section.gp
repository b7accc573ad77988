# The XFEM solution of "pull" (corotated, 3x6x19 Tet4) on the mid-plane y = 0.03: each point of a
# grid moved by the field of its own side of the cut; the gap is the opened cut.
load "common.gp"
set terminal pngcairo size 900,800 enhanced font "DejaVu Sans,11"
set output "section.png"
set title "Deformed mid-section y = 0.03 near the cut, XFEM (pull, corotated, 3x6x19 Tet4)\nthe rectangle ends at x = 0.015; the cells are 0.01 wide"
set size ratio -1
set xrange [-0.01:0.04]
set yrange [0.06:0.15]
set xtics 0.01
set key outside bottom center horizontal
set xlabel "x + u_x (m)"
set ylabel "z + u_z (m)"
set key bottom right box opaque
plot "section.csv" using ($3 == 1 ? $4 : NaN):5 w p pt 7 ps 0.25 lc rgb "#d62728" t "above the cut plane (z > 0.1)", \
     "" using ($3 == 0 ? $4 : NaN):5 w p pt 7 ps 0.25 lc rgb "#1f77b4" t "below"
