# Error against CalculiX NLGEOM: against the deflection, and against the wall time of a solve.
load "common.gp"
set output "error.png"
set multiplot layout 1,2 title "Tip error against CalculiX NLGEOM on the same C3D10 mesh" font ",13"
set logscale y
set format y "10^{%L}"
set ylabel "relative tip error |u_{tip} - u_{tip}^{ccx}| / |u_{tip}^{ccx}|"
set xlabel "tip deflection u_x^{ccx} / L (%)"
set title "error against deflection"
set key at graph 0.98, graph 0.45 box opaque font ",10"
L = 0.2
plot "load.csv" using (100*$10/L):12 w lp ls 1 t "linear FEM (Tet10)", \
     "" using (100*$10/L):24 w lp ls 2 t "linear FEM, u_x alone", \
     "" using (100*$10/L):13 w lp ls 3 t "corotated Tet10", \
     "" using (100*$10/L):14 w lp ls 5 t "corotated Tet4", \
     "" using (100*$10/L):15 w l ls 7 t "elastica", \
     0.01 w l ls 9 t "1 %"
set logscale x
set format x "10^{%L}"
set xlabel "wall time per solve (s), one core of a shared machine"
set title "error against cost"
set key default
set key top right box opaque font ",10"
plot "load.csv" using 18:12 w p ls 1 t "linear FEM (Tet10)", \
     "" using 19:13 w p ls 3 t "corotated Tet10", \
     "" using 20:14 w p ls 5 t "corotated Tet4", \
     "" using 21:(1e-5) w p ls 6 t "CalculiX NLGEOM run (placed at 10^{-5})"
unset multiplot
