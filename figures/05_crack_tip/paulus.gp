# Paulus Fig. 9 again: error against unknowns on the beam with the half-depth cut (paulus.csv,
# written by examples/05_paulus_study.cpp; make_paulus_figures.sh runs both).
set terminal pngcairo size 1400,560 font ",11"
set output 'paulus.png'
set datafile separator ','
set datafile missing NaN
set logscale xy
set grid
set xlabel 'free unknowns'
set ylabel 'relative L2 error against the conforming Tet10 6x12x40'
set key bottom left
set multiplot layout 1,2
pick(load, method) = (strcol(1) eq load && strcol(2) eq method) ? $4 : NaN
titles = "'gravity 9.81 m/s^2 along +x' 'tip traction: 1 N along +z on the face z = 0.2'"
do for [i = 1:2] {
  load = word("gravity tip_traction", i)
  set title word(titles, i)
  plot 'paulus.csv' using (pick(load, "conforming4")):6 smooth unique with linespoints pt 4 title 'conforming Tet4', \
       '' using (pick(load, "conforming10")):6 smooth unique with linespoints pt 5 title 'conforming Tet10', \
       '' using (pick(load, "xfem_heaviside")):6 smooth unique with linespoints pt 6 title 'XFEM Tet4, Heaviside only', \
       '' using (pick(load, "xfem_topological")):6 smooth unique with linespoints pt 8 title 'XFEM Tet4, topological branch', \
       '' using (pick(load, "xfem_geometric")):6 smooth unique with linespoints pt 7 title 'XFEM Tet4, geometric branch', \
       '' using (pick(load, "check10")):6 with points pt 3 ps 2 title 'conforming Tet10 4x8x26 (reference check)'
}
unset multiplot
