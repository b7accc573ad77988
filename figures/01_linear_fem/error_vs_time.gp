# Relative L2 error versus the wall time of set-up + assembly + solve (one core, best of 3).
load "common.gp"
set terminal pngcairo size 700,520 enhanced font "DejaVu Sans,11" linewidth 1.5
set output "error_vs_time.png"
set logscale xy
set format x "10^{%L}"
set xlabel "wall time of set-up + assembly + CHOLMOD solve (s), one core"
set ylabel "relative L2 error"
set title "Chapter 1 beam: accuracy bought per second"
set key top right box opaque
plot "ladder.csv" using (pick("Tet4","gravity",9)):(pick("Tet4","gravity",10)) w lp ls 1 t "Tet4, gravity", \
     "" using (pick("Tet4","traction",9)):(pick("Tet4","traction",10)) w lp ls 2 t "Tet4, traction", \
     "" using (pick("Tet10","gravity",9)):(pick("Tet10","gravity",10)) w lp ls 3 t "Tet10, gravity", \
     "" using (pick("Tet10","traction",9)):(pick("Tet10","traction",10)) w lp ls 4 t "Tet10, traction"
