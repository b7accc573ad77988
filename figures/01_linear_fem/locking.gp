# Volumetric locking: errors on one fixed mesh as nu -> 0.5, against a Tet10 reference at the same nu.
load "common.gp"
set output "locking.png"
set multiplot layout 1,2 title "Chapter 1 beam under gravity, cells 3x6x20, E fixed: locking as {/Symbol n} -> 0.5"
set logscale xy
# The top axis reads the same positions as Poisson's ratios: same range, same log scale.
set logscale x2
set xrange [3:2e4]
set x2range [3:2e4]
set format x "10^{%L}"
set xlabel "1 / (0.5 - {/Symbol n})   (top axis: Poisson's ratio {/Symbol n})"
set key bottom right box opaque
only(element, column) = strcol(1) eq element ? column(column) : NaN
inv(nu) = 1.0 / (0.5 - nu)
set x2tics ("0.3" 5, "0.4" 10, "0.45" 20, "0.49" 100, "0.499" 1000, "0.4999" 10000) font ",9"
set ylabel "relative L2 error"
set title "L2 norm of the displacement error"
plot "locking.csv" using (inv(only("Tet4",2))):(only("Tet4",5)) w lp ls 1 t "Tet4", \
     "" using (inv(only("Tet10",2))):(only("Tet10",5)) w lp ls 3 t "Tet10"
set format y "%g"
unset logscale y
set yrange [0:1.1]
set ylabel "tip displacement u_x / reference u_x"
set title "Tip deflection relative to the reference"
set key bottom left box opaque
plot "locking.csv" using (inv(only("Tet4",2))):(only("Tet4",7)/only("Tet4",8)) w lp ls 1 t "Tet4", \
     "" using (inv(only("Tet10",2))):(only("Tet10",7)/only("Tet10",8)) w lp ls 3 t "Tet10", \
     1 w l ls 9 t "reference"
unset multiplot
