# Which rule is worth its cost: Tet10 XFEM (and Tet4) on the cut beam with every piece rule.
# Left: the error against unknowns (the rules exact to degree 2 coincide); right: the set-up time
# (cut processing, the rules, the model) against unknowns. curved_ladder.csv.
set terminal pngcairo size 1300,1000 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
# A row another curve owns gives NaN: skipped without breaking the line, so each ladder is one curve.
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set output "curved_rules.png"
pick(cut, method, rule, c) = (strcol(1) eq cut && strcol(2) eq method && strcol(3) eq rule) ? column(c) : NaN
set style line 1 lc rgb "#2ca02c" pt 9 ps 1.6 lw 2          # subtets
set style line 2 lc rgb "#d62728" pt 7 ps 0.9 lw 1.5        # exact
set style line 3 lc rgb "#9467bd" pt 5 ps 0.9 lw 1.5        # moment fitting
set style line 4 lc rgb "#1f77b4" pt 6 ps 1.2 lw 1.5        # lattice
set style line 5 lc rgb "#7f7f7f" pt 13 ps 1.2 lw 1.5       # volume ratio
set style line 6 lc rgb "#ff7f0e" pt 4 ps 1.2 lw 1.5 dt 2   # Tet4 volume ratio
set logscale xy
set format x "10^{%L}"
set format y "10^{%L}"
set key bottom left box opaque font ",9"
set multiplot layout 2,2 title "Tet10 XFEM with each piece rule (Tet4 with subtets and volume ratios for comparison)" font ",13"
do for [cut in "dome ridge"] {
  do for [ycol in "8 7"] {
    set title cut.(ycol eq "8" ? ": error against unknowns" : ": set-up time (cut, rules, model) against unknowns")
    set xlabel "free unknowns"
    set ylabel (ycol eq "8" ? "||u_h - u_{ref}|| / ||u_{ref}||" : "seconds")
    c = int(ycol)
    if (ycol eq "7") { set key top left box opaque font ",9" } else { set key bottom left box opaque font ",9" }
    plot "curved_ladder.csv" using (pick(cut, "xfem10", "subtets", 5)):(pick(cut, "xfem10", "subtets", c)) w lp ls 1 t "Tet10 subtets", \
         "" using (pick(cut, "xfem10", "exact", 5)):(pick(cut, "xfem10", "exact", c)) w lp ls 2 t "Tet10 exact", \
         "" using (pick(cut, "xfem10", "moment_fitting", 5)):(pick(cut, "xfem10", "moment_fitting", c)) w lp ls 3 t "Tet10 Koschier moment fitting", \
         "" using (pick(cut, "xfem10", "lattice", 5)):(pick(cut, "xfem10", "lattice", c)) w lp ls 4 t "Tet10 lattice (125 sub-tets)", \
         "" using (pick(cut, "xfem10", "volume_ratio", 5)):(pick(cut, "xfem10", "volume_ratio", c)) w lp ls 5 t "Tet10 volume ratio", \
         "" using (pick(cut, "xfem4", "subtets", 5)):(pick(cut, "xfem4", "subtets", c)) w lp ls 6 lc rgb "#333333" t "Tet4 subtets", \
         "" using (pick(cut, "xfem4", "volume_ratio", 5)):(pick(cut, "xfem4", "volume_ratio", c)) w lp ls 6 t "Tet4 volume ratio"
  }
}
unset multiplot
