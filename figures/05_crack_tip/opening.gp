# Chapter 5's opening study (examples/05_opening_study.cpp, opening.csv): the demo's crack-mouth
# opening. Left: under the demo's edge forces applied as point loads, against the cell width h,
# conforming and XFEM ladders, with the reference (the mean of their extrapolated limits,
# opening_reference.csv) and the demo itself. Right: the edge's prescribed displacement on
# conforming meshes: 1 / F against h (a straight line on a log axis is F ~ 1 / ln(1 / h)), cut and
# uncut, and the cut beam's opening.
set terminal pngcairo size 1300,520 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing "nan"
set grid xtics ytics mxtics lc rgb "#dddddd"
set output "opening.png"
# opening.csv: 1 part, 2 method, 3 forces_of, 5 h, 9 opening_mouth, 11 force; one ladder's rows,
# contiguous so that its points are joined:
rows(part, method, forces) = sprintf("< awk -F, '$1 == \"%s\" && $2 == \"%s\" && $3 == \"%s\"' opening.csv", part, method, forces)
stats "opening_reference.csv" using ((strcol(1) eq "points" && strcol(2) eq "default") ? 1000 * $4 : NaN) nooutput name "REF"
stats "opening.csv" using ((strcol(1) eq "demo" && strcol(2) eq "default") ? 1000 * $9 : NaN) nooutput name "DEMO"
set multiplot layout 1,2 title "Chapter 5's demo: the opening at the crack's mouth (x = 0, y = 0.03)" font ",13"
set logscale x
set xlabel "cell width h (m)"
set ylabel "opening (mm)"
set key bottom right box opaque font ",9"
set title "under the demo's edge forces (point loads), edge free"
set yrange [3:14]
set xrange [0.001:0.02]
plot rows("points", "conforming", "default") using 5:(1000 * $9) w lp pt 9 lc rgb "#2ca02c" t "conforming (cut in the mesh)", \
     rows("points", "radius_0.01", "default") using 5:(1000 * $9) w lp pt 7 lc rgb "#d62728" t "XFEM, r_e = 0.01 m", \
     rows("points", "default", "default") using 5:(1000 * $9) w lp pt 5 lc rgb "#9467bd" t "XFEM, default r_e (the demo refined)", \
     rows("points", "topological", "default") using 5:(1000 * $9) w lp pt 13 lc rgb "#1f77b4" t "XFEM, topological", \
     REF_mean w l dt 2 lc rgb "#000000" t sprintf("reference %.2f mm", REF_mean), \
     "+" using (0.01):(DEMO_mean) every ::0::0 w p pt 3 ps 2 lc rgb "#000000" t sprintf("the demo, 3x6x19: %.2f mm", DEMO_mean)
set title "the edge moved by 0.02 m (prescribed on a line), conforming"
set yrange [*:*]
set xrange [0.001:0.02]
set ylabel "1 / F (1/N)"
set y2label "opening (mm)"
set y2tics
set ytics nomirror
set key top right box opaque font ",9"
plot rows("line", "uncut", "-") using 5:(1 / $11) w lp pt 4 lc rgb "#1f77b4" t "1 / F, uncut", \
     rows("line", "conforming", "-") using 5:(1 / $11) w lp pt 5 lc rgb "#2ca02c" t "1 / F, cut", \
     rows("line", "conforming", "-") using 5:(1000 * $9) axes x1y2 w lp pt 7 lc rgb "#d62728" t "opening, cut (right axis)"
unset multiplot
