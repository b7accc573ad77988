# Relative L2 error against the reference, against the wall time of one solve.
load "common.gp"
set output "ladder_time.png"
set multiplot layout 2,3 title "Relative L2 error against the fine conforming Tet10 reference, against wall time of one solve" font ",13"
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set xrange [*:*]
set yrange [0.005:1.5]
set key bottom left box opaque font ",9"
do for [model in "linear corot"] {
  do for [case in "gravity pull move"] {
    set title case." (".model.")"
    set xlabel "seconds, one core of a shared machine"
    set ylabel "||u_h - u_{ref}|| / ||u_{ref}||"
    plot "ladder.csv" using (pick(case, model, "xfem", 6)):(pick(case, model, "xfem", 9)) w lp ls 1 t "XFEM Tet4", \
         "" using (pick(case, model, "conforming", 6)):(pick(case, model, "conforming", 9)) w lp ls 2 t "conforming Tet4", \
         "" using (pick(case, model, "conforming10", 6)):(pick(case, model, "conforming10", 9)) w lp ls 3 t "conforming Tet10"
  }
}
unset multiplot
