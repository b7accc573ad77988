# The cut plane a distance d above a node layer: condition number of K_ff and the difference
# from the cut exactly on the layer, with the minimum-fraction rule (1e-4) and without.
load "common.gp"
set output "fraction.png"
set multiplot layout 1,2 title "A sliver piece: the cut plane at z = 0.1 + d on the 4x4x10 mesh (front x = 0.015 on a node layer)" font ",13"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xlabel "d / h: the plane's distance above the node layer, in cell heights"
set xrange [*:*] reverse
set title "condition number of K_{ff} (dense eigenvalues)"
set yrange [1e3:1e18]
set key top left box opaque font ",9"
plot "fraction.csv" using (pickf("on_layer", 0, 3)):(pickf("on_layer", 0, 13)) w p ls 1 t "rule off", \
     "" using (pickf("on_layer", 1e-4, 3)):(pickf("on_layer", 1e-4, 13)) w p ls 2 t "minimum fraction 10^{-4}", \
     "" using (pickf("on_layer", 0, 3)):(pickf("on_layer", 0, 14)) w p ls 4 t "rule off, Jacobi-scaled", \
     "" using (pickf("on_layer", 1e-4, 3)):(pickf("on_layer", 1e-4, 14)) w p ls 3 t "10^{-4}, Jacobi-scaled"
set title "difference from the solution with the cut on the layer"
set ylabel "relative L2 difference (outside the slab 0.1 < z < 0.1 + d)"
set key bottom left box opaque font ",9"
set yrange [1e-16:1]
plot "fraction.csv" using (pickf("on_layer", 0, 3)):(pickf("on_layer", 0, 15)) w p ls 1 t "front on a layer, rule off", \
     "" using (pickf("on_layer", 1e-4, 3)):(pickf("on_layer", 1e-4, 15) > 1e-15 ? pickf("on_layer", 1e-4, 15) : 1e-15) w p ls 2 t "front on a layer, 10^{-4} (below 10^{-15} drawn at 10^{-15})", \
     "" using (pickf("mid_cell", 0, 3)):(pickf("mid_cell", 0, 15)) w p ls 4 t "front mid-cell (3x4x10), rule off", \
     "" using (pickf("mid_cell", 1e-4, 3)):(pickf("mid_cell", 1e-4, 15) > 1e-15 ? pickf("mid_cell", 1e-4, 15) : 1e-15) w p ls 3 t "front mid-cell, 10^{-4} (below 10^{-15} drawn at 10^{-15})"
unset multiplot
