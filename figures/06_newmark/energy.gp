# Chapter 6's energy chart from the energy.csv files that make_figures.sh keeps here.
set terminal pngcairo size 1100,800 font ",11"
set output "energy.png"
set datafile separator ","
set datafile missing NaN
set multiplot layout 2,1
set xlabel "t (s)"
set ylabel "energy (J)"
set key top left
set grid
set title "The demo (corotational, rotations frozen per step): where gravity's work went"
plot "energy_demo_frozen.csv" every ::1 using 2:3 with lines lw 2 title "kinetic", \
     "" every ::1 using 2:4 with lines lw 2 title "elastic (corotated strain energy)", \
     "" every ::1 using 2:5 with lines lw 2 title "external work", \
     "" every ::1 using 2:6 with lines lw 2 title "dissipated (damping + integrator)"
set title "kinetic + elastic: frozen rotations, Newton per step, and linear XFEM"
plot "energy_demo_frozen.csv" every ::1 using 2:($3+$4) with lines lw 2 title "corotational, frozen", \
     "energy_demo_newton.csv" every ::1 using 2:($3+$4) with lines lw 2 dt 2 title "corotational, Newton", \
     "energy_flap_linear.csv" every ::1 using 2:($3+$4) with lines lw 2 title "linear XFEM"
unset multiplot
