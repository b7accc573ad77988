# Whole-run process wall time, Kerf's chapter 1 program against CalculiX, on the same meshes.
load "common.gp"
set terminal pngcairo size 700,520 enhanced font "DejaVu Sans,11" linewidth 1.5
set output "kerf_vs_calculix.png"
set logscale xy
set format x "10^{%L}"
set format y "%g"
set xlabel "unknowns (free DOFs)"
set ylabel "process wall time (s), one core"
set title "Whole static run under gravity: Kerf (01\\_linear\\_fem) and CalculiX (ccx)"
set key top left box opaque
# The study writes gravity and traction rows alternately; keeping only the gravity rows (and
# the header) makes each element's points contiguous, so gnuplot joins them into one line.
gravity_rows = "< awk -F, 'NR == 1 || $2 == \"gravity\"' calculix.csv"
plot gravity_rows using (pick("Tet4","gravity",4)):(pick("Tet4","gravity",7)) w lp ls 1 t "Kerf, Tet4", \
     "" using (pick("Tet10","gravity",4)):(pick("Tet10","gravity",7)) w lp ls 3 t "Kerf, Tet10", \
     "" using (pick("Tet4","gravity",4)):(pick("Tet4","gravity",8)) w lp ls 2 t "CalculiX, C3D4", \
     "" using (pick("Tet10","gravity",4)):(pick("Tet10","gravity",8)) w lp ls 4 t "CalculiX, C3D10"
