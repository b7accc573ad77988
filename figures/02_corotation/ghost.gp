# Ghost forces: the beam turned rigidly by its end faces, linear FEM against corotated FEM.
load "common.gp"
set output "ghost.png"
set multiplot layout 1,2 title "Beam turned rigidly (both end faces prescribed): what should be zero" font ",13"
set xlabel "rotation angle (degrees)"
set xrange [0:185]
set xtics 30
set logscale y
set format y "10^{%L}"
set yrange [1e-17:1e4]
set ylabel "strain energy |E| (J)"
set title "strain energy (linear: 1/2 u^T K u; corotated: its own energy)"
set key at graph 0.98, graph 0.62 box opaque font ",10"
plot "ghost.csv" using (pick("Tet4","z",3)):(pick("Tet4","z",4)) w lp ls 1 t "linear Tet4, about z (long axis)", \
     "" using (pick("Tet4","y",3)):(pick("Tet4","y",4)) w lp ls 2 t "linear Tet4, about y", \
     "" using (pick("Tet10","z",3)):(pick("Tet10","z",4)) w l lc rgb "#17becf" lw 2 t "linear Tet10, about z", \
     "" using (pick("Tet10","y",3)):(pick("Tet10","y",4)) w l lc rgb "#17becf" lw 2 dt 2 t "linear Tet10, about y", \
     "" using (pick("Tet4","z",3)):(abs(pick("Tet4","z",8))) w lp ls 3 t "corotated Tet4, about z", \
     "" using (pick("Tet4","y",3)):(abs(pick("Tet4","y",8))) w lp ls 4 t "corotated Tet4, about y", \
     "" using (pick("Tet10","z",3)):(abs(pick("Tet10","z",8))) w lp ls 5 t "corotated Tet10, about z", \
     "" using (pick("Tet10","y",3)):(abs(pick("Tet10","y",8))) w lp ls 5 dt 2 pt 8 t "corotated Tet10, about y"
unset logscale y
set format y "%g"
set yrange [*:*]
set ylabel "relative volume change V_{deformed} / V - 1"
set title "volume change of the deformed mesh"
set key default
set key bottom left box opaque font ",10"
plot "ghost.csv" using (pick("Tet4","z",3)):(pick("Tet4","z",5)) w lp ls 1 t "linear Tet4, about z", \
     "" using (pick("Tet4","y",3)):(pick("Tet4","y",5)) w lp ls 2 t "linear Tet4, about y", \
     "" using (pick("Tet10","z",3)):(pick("Tet10","z",5)) w l lc rgb "#17becf" lw 2 t "linear Tet10, about z", \
     "" using (pick("Tet10","y",3)):(pick("Tet10","y",5)) w l lc rgb "#17becf" lw 2 dt 2 t "linear Tet10, about y", \
     "" using (pick("Tet4","z",3)):(pick("Tet4","z",9)) w lp ls 3 t "corotated Tet4 (both axes)", \
     "" using (pick("Tet10","y",3)):(pick("Tet10","y",9)) w lp ls 5 t "corotated Tet10 (both axes)"
unset multiplot
