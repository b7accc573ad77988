# The beam cut clean through by the dome and by the ridge: relative L2 error against the fine
# conforming Tet10 reference, against free unknowns (left) and wall time (right). XFEM on box
# meshes that ignore the cut (subtets rule), beside conforming Tet4 and Tet10 meshes opened along
# it. curved_ladder.csv, written by 04_curved_cut_study.
set terminal pngcairo size 1300,1000 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
# A row another curve owns gives NaN: skipped without breaking the line, so each ladder is one curve.
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "curved_ladder.png"
# curved_ladder.csv rows kept only where cut, method and rule match.
pick(cut, method, rule, c) = (strcol(1) eq cut && strcol(2) eq method && strcol(3) eq rule) ? column(c) : NaN
set style line 1 lc rgb "#d62728" pt 7 ps 1.0 lw 2          # XFEM Tet4
set style line 2 lc rgb "#1f77b4" pt 5 ps 1.0 lw 2          # conforming Tet4
set style line 3 lc rgb "#2ca02c" pt 9 ps 1.2 lw 2          # conforming Tet10
set style line 4 lc rgb "#9467bd" pt 11 ps 1.2 lw 2         # XFEM Tet10
set style line 9 lc rgb "#777777" lw 1 dt 3                 # guides
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set key bottom left box opaque font ",9"
set multiplot layout 2,2 title "Beam cut clean through (A = 10 mm): relative L2 error against the conforming Tet10 reference 10x20x50" font ",13"
do for [cut in "dome ridge"] {
  do for [xcol in "5 6"] {
    set title cut.(xcol eq "5" ? ": error against unknowns" : ": error against wall time (geometry to displacements, one core)")
    set xlabel (xcol eq "5" ? "free unknowns" : "seconds")
    set ylabel "||u_h - u_{ref}|| / ||u_{ref}||"
    c = int(xcol)
    plot "curved_ladder.csv" using (pick(cut, "xfem4", "subtets", c)):(pick(cut, "xfem4", "subtets", 8)) w lp ls 1 t "XFEM Tet4", \
         "" using (pick(cut, "conforming", "-", c)):(pick(cut, "conforming", "-", 8)) w lp ls 2 t "conforming Tet4", \
         "" using (pick(cut, "xfem10", "subtets", c)):(pick(cut, "xfem10", "subtets", 8)) w lp ls 4 t "XFEM Tet10", \
         "" using (pick(cut, "conforming10", "-", c)):(pick(cut, "conforming10", "-", 8)) w lp ls 3 t "conforming Tet10", \
         (xcol eq "5" ? 3.0*(x/100.0)**(-1.0/3) : NaN) w l ls 9 t (xcol eq "5" ? "unknowns^{-1/3} (h^1)" : ""), \
         (xcol eq "5" ? 0.5*(x/500.0)**(-2.0/3) : NaN) w l ls 9 dt 4 t (xcol eq "5" ? "unknowns^{-2/3} (h^2)" : "")
  }
}
unset multiplot
