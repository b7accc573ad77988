# Relative errors against the Tet10 reference, versus the number of unknowns (log-log).
load "common.gp"
set output "error_vs_dofs.png"
set multiplot layout 1,2 title "Chapter 1 beam: error against a converged Tet10 reference"
set logscale xy
set format x "10^{%L}"
set xlabel "unknowns (free DOFs)"
set key bottom left box opaque
# Slope guides: h ~ DOFs^(-1/3), so an error of order h^p falls like DOFs^(-p/3).
set ylabel "relative L2 error ||u_h - u_{ref}|| / ||u_{ref}||"
set title "L2 norm of the displacement error"
plot "ladder.csv" using (pick("Tet4","gravity",5)):(pick("Tet4","gravity",10)) w lp ls 1 t "Tet4, gravity", \
     "" using (pick("Tet4","traction",5)):(pick("Tet4","traction",10)) w lp ls 2 t "Tet4, traction", \
     "" using (pick("Tet10","gravity",5)):(pick("Tet10","gravity",10)) w lp ls 3 t "Tet10, gravity", \
     "" using (pick("Tet10","traction",5)):(pick("Tet10","traction",10)) w lp ls 4 t "Tet10, traction", \
     [300:2e5] 40*x**(-2./3) w l ls 9 t "slope -2/3 (h^2)", \
     [300:1e5] 40*x**(-1.) w l ls 9 dt 4 t "slope -1 (h^3)"
set ylabel "relative error of u_x at the tip (0.015, 0.03, 0.2) m"
set title "x-displacement at the centre of the top face"
plot "ladder.csv" using (pick("Tet4","gravity",5)):(pick("Tet4","gravity",11)) w lp ls 1 t "Tet4, gravity", \
     "" using (pick("Tet4","traction",5)):(pick("Tet4","traction",11)) w lp ls 2 t "Tet4, traction", \
     "" using (pick("Tet10","gravity",5)):(pick("Tet10","gravity",11)) w lp ls 3 t "Tet10, gravity", \
     "" using (pick("Tet10","traction",5)):(pick("Tet10","traction",11)) w lp ls 4 t "Tet10, traction", \
     [300:2e5] 40*x**(-2./3) w l ls 9 t "slope -2/3 (h^2)", \
     [300:1e5] 40*x**(-1.) w l ls 9 dt 4 t "slope -1 (h^3)"
unset multiplot
