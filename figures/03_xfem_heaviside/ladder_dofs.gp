# Relative L2 error against the reference, against the number of unknowns: XFEM on meshes that
# do not conform to the cut, and conforming FEM (cut opened by duplicated nodes), Tet4 and Tet10.
load "common.gp"
set output "ladder_dofs.png"
set multiplot layout 2,3 title "Relative L2 error against the fine conforming Tet10 reference, against DOFs" font ",13"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [80:50000]
set yrange [0.005:1.5]
set key bottom left box opaque font ",9"
do for [model in "linear corot"] {
  do for [case in "gravity pull move"] {
    set title case." (".model.")"
    set xlabel "free DOFs"
    set ylabel "||u_h - u_{ref}|| / ||u_{ref}||"
    plot "ladder.csv" using (pick(case, model, "xfem", 5)):(pick(case, model, "xfem", 9)) w lp ls 1 t "XFEM Tet4", \
         "" using (pick(case, model, "conforming", 5)):(pick(case, model, "conforming", 9)) w lp ls 2 t "conforming Tet4", \
         "" using (pick(case, model, "conforming10", 5)):(pick(case, model, "conforming10", 9)) w lp ls 3 t "conforming Tet10", \
         2.0*(x/100.0)**(-1.0/3) w l ls 9 t "DOFs^{-1/3} (h^1)"
  }
}
unset multiplot
