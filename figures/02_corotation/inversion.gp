# One Tet4 squeezed through zero volume: Higham's rotation against the SVD rotation.
load "common.gp"
set output "inversion.png"
set multiplot layout 1,2 title "One Tet4 (h = 1 cm): corner 3 pushed through the opposite face, det F from 1 to -0.5" font ",13"
set xlabel "det F"
set xrange [1.02:-0.52]
set arrow 1 from 0, graph 0 to 0, graph 1 nohead ls 9
set ylabel "force of the element on the corner, along +z (N)"
set title "force (> 0 pushes the corner back out)"
set key top left box opaque font ",10"
plot "inversion.csv" using 1:6 w lp ls 1 t "corotated, Higham's R (reflection past 0)", \
     "" using 1:10 w lp ls 3 t "corotated, SVD rotation", \
     "" using 1:2 w l ls 7 t "linear FEM", \
     0 w l ls 9 notitle
set ylabel "element strain energy (J)"
set title "energy"
set key top left box opaque font ",10"
plot "inversion.csv" using 1:8 w lp ls 1 t "corotated, Higham's R", \
     "" using 1:12 w lp ls 3 t "corotated, SVD rotation", \
     "" using 1:3 w l ls 7 t "linear FEM"
unset multiplot
