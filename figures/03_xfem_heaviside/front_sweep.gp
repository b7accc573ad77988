# The front swept through the elements: the tip deflection u_x at (0.03, 0.03, 0.2) under gravity
# (linear) against the rectangle's depth x1, XFEM on uniform meshes that ignore the cut against
# conforming meshes fitted to every x1; and what the enrichment made of the cut. front_sweep.csv.
load "common.gp"
set output "front_sweep.png"
# front_sweep.csv rows of one XFEM mesh and plane.
picks(cells, z, column) = (strcol(1) eq cells && abs(column(2) - z) < 1e-9) ? column(column) : NaN
separated(cells, z, y) = (strcol(1) eq cells && abs(column(2) - z) < 1e-9 && strcol(4) eq "separated") ? y : NaN
set multiplot layout 1,2 title "The cut's front swept through the elements: gravity, linear, tip u_x at (0.03, 0.03, 0.2)" font ",13"
set xlabel "x1: depth of the cut (mm of 30; cells of 3x6x19: 10 mm)"
set xrange [0:30]
set xtics 5
set mxtics 5
set title "tip deflection"
set ylabel "u_x (m)"
set logscale y
set yrange [0.04:1.0]
set ytics (0.04, 0.05, 0.06, 0.07, 0.08, 0.1, 0.12, 0.15, 0.2, 0.3, 0.5, 0.7, 1.0)
set arrow 1 from 10, graph 0 to 10, graph 1 nohead ls 9
set arrow 2 from 20, graph 0 to 20, graph 1 nohead ls 9
set key top left box opaque font ",9"
plot "front_sweep.csv" using (1000*picks("3x6x19", 0.1, 3)):(picks("3x6x19", 0.1, 10)) w lp ls 1 t "XFEM 3x6x19, plane z = 0.1", \
     "" using (1000*picks("3x6x19", 0.1003, 3)):(picks("3x6x19", 0.1003, 10)) w lp ls 4 t "XFEM 3x6x19, plane z = 0.1003", \
     "" using (1000*picks("5x10x31", 0.1003, 3)):(picks("5x10x31", 0.1003, 10)) w lp lc rgb "#9467bd" pt 13 ps 0.8 lw 2 t "XFEM 5x10x31, plane z = 0.1003", \
     "" using (1000*picks("3x6x19", 0.1003, 3)):(picks("3x6x19", 0.1003, 11)) w l ls 2 t "conforming Tet4 3x6x20, fitted to x1", \
     "" using (1000*picks("3x6x19", 0.1003, 3)):(picks("3x6x19", 0.1003, 12)) w l ls 3 t "conforming Tet10 4x8x20, fitted to x1", \
     "" using (1000*picks("3x6x19", 0.1003, 3)):(separated("3x6x19", 0.1003, 0.85)) w p lc rgb "#ff7f0e" pt 2 ps 1.2 t "3x6x19: the top separated (0.1003; 0.1 alike)", \
     "" using (1000*picks("5x10x31", 0.1003, 3)):(separated("5x10x31", 0.1003, 0.75)) w p lc rgb "#9467bd" pt 2 ps 1.2 t "5x10x31: the top separated"
set title "what the enrichment made of it (3x6x19; the enriched nodes are the same on both planes)" font ",10"
set ylabel "count"
unset logscale y
set ytics auto
set yrange [0:60]
set key top left box opaque font ",9"
plot "front_sweep.csv" using (1000*picks("3x6x19", 0.1003, 3)):(picks("3x6x19", 0.1003, 5)) w steps ls 1 t "enriched nodes, z = 0.1003", \
     "" using (1000*picks("3x6x19", 0.1003, 3)):(picks("3x6x19", 0.1003, 8)) w p ls 2 t "partially cut tets, z = 0.1003", \
     "" using (1000*picks("3x6x19", 0.1, 3)):(picks("3x6x19", 0.1, 5)) w steps ls 4 t "enriched nodes, z = 0.1", \
     "" using (1000*picks("3x6x19", 0.1, 3)):(picks("3x6x19", 0.1, 8)) w p ls 3 t "partially cut tets, z = 0.1"
unset multiplot
