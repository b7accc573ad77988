# The flap's free end (probe 0) and the beam below the cut (probe 1) over time, from the
# histories make_figures.sh keeps here: ux along gravity, uz along the beam.
set terminal pngcairo size 1100,800 font ",11"
set output "flap_tip.png"
set datafile separator ","
set datafile missing NaN
set multiplot layout 2,1
set xlabel "t (s)"
set grid
set key top right
set ylabel "u_x (m)"
set title "The flap's free end (0.015, 0.03, 0.195): displacement along gravity"
plot "history_demo_frozen.csv" using 2:($3 == 0 ? $4 : NaN) with lines lw 2 title "corotational, frozen", \
     "history_demo_newton.csv" using 2:($3 == 0 ? $4 : NaN) with lines lw 2 dt 2 title "corotational, Newton", \
     "history_flap_linear.csv" using 2:($3 == 0 ? $4 : NaN) with lines lw 2 title "linear XFEM", \
     "history_demo_frozen.csv" using 2:($3 == 1 ? $4 : NaN) with lines lw 1 title "beam below the cut, frozen"
set ylabel "u_z (m)"
set title "The same point along the beam's axis: turning with the beam it drops (corotational); linear XFEM moves it straight sideways"
plot "history_demo_frozen.csv" using 2:($3 == 0 ? $6 : NaN) with lines lw 2 title "corotational, frozen", \
     "history_demo_newton.csv" using 2:($3 == 0 ? $6 : NaN) with lines lw 2 dt 2 title "corotational, Newton", \
     "history_flap_linear.csv" using 2:($3 == 0 ? $6 : NaN) with lines lw 2 title "linear XFEM"
unset multiplot
