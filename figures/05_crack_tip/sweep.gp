# Chapter 3's front sweep with branch functions (sweep.csv, examples/05_paulus_study.cpp --only sweep),
# beside chapter 3's conforming Tet10 fitted to every x1 (../03_xfem_heaviside/front_sweep.csv).
set terminal pngcairo size 1400,560 font ",11"
set output 'sweep.png'
set datafile separator ','
set datafile missing NaN
set grid
set xlabel 'front position x1 (mm)'
set ylabel 'tip u_x at (0.03, 0.03, 0.2) (mm)'
set key top left
pick(t) = (strcol(2) eq t && strcol(3) eq "solved") ? 1000 * $1 : NaN
ch3(x) = (strcol(1) eq "3x6x19" && $2 == 0.1003) ? 1000 * $3 : NaN
set multiplot layout 1,2
set title 'gravity, XFEM Tet4 3x6x19, cut plane z = 0.1003'
set xrange [0:25]
set yrange [40:300]
plot 'sweep.csv' using (pick("heaviside")):(1000*$6) with linespoints pt 6 title 'Heaviside only (chapter 4)', \
     '' using (pick("topological")):(1000*$6) with linespoints pt 8 title 'topological branch', \
     '' using (pick("geometric")):(1000*$6) with linespoints pt 7 title 'geometric branch', \
     '../03_xfem_heaviside/front_sweep.csv' using (ch3(0)):(1000*$12) with lines lw 2 title 'conforming Tet10 4x8x20 (chapter 3)'
set title 'the same, 0.1 mm steps across the node row x = 0.01'
set xrange [8.9:11.1]
set autoscale y
plot 'sweep.csv' using (pick("heaviside")):(1000*$6) with linespoints pt 6 title 'Heaviside only', \
     '' using (pick("topological")):(1000*$6) with linespoints pt 8 title 'topological branch', \
     '' using (pick("geometric")):(1000*$6) with linespoints pt 7 title 'geometric branch'
unset multiplot
