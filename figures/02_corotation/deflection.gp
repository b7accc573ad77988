# Tip displacement of the cantilever against the load, every method and the elastica.
load "common.gp"
set output "deflection.png"
set multiplot layout 1,2 title "Cantilever 0.03 x 0.06 x 0.2 m, dead load on the top face along +x (tip = mean of top-face nodes)" font ",13"
set xlabel "total load P (N)"
set key top left box opaque font ",10"
set ylabel "tip displacement along the load u_x (m)"
set title "deflection along the load"
plot "load.csv" using 1:4 w lp ls 1 t "linear FEM (Tet10)", \
     "" using 1:6 w lp ls 3 t "corotated Tet10", \
     "" using 1:8 w lp ls 5 t "corotated Tet4", \
     "" using 1:10 w lp ls 6 t "CalculiX NLGEOM (C3D10)", \
     "" using 1:2 w l ls 7 t "elastica (Euler-Bernoulli)"
set ylabel "tip displacement along the axis u_z (m)"
set title "shortening along the beam axis"
set key bottom left box opaque font ",10"
plot "load.csv" using 1:5 w lp ls 1 t "linear FEM (Tet10)", \
     "" using 1:7 w lp ls 3 t "corotated Tet10", \
     "" using 1:9 w lp ls 5 t "corotated Tet4", \
     "" using 1:11 w lp ls 6 t "CalculiX NLGEOM (C3D10)", \
     "" using 1:3 w l ls 7 t "elastica (Euler-Bernoulli)"
unset multiplot
