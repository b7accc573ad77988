# Koschier's Fig. 14 again (examples/06_conditioning_study.cpp), two charts from conditioning_sweep.csv:
# conditioning_sweep.png: the 2-norm condition number of A = M + dt^2 K of the five-tet cube
# [-1, 1]^3 against the cut position x_c (semi-log, as the paper's figure), five variants, and
# the uncut cube's as a line;
# conditioning_growth.png: the same against the distance d of the cut from the face it nears
# (log-log, the cut nearing x = -1), with the slopes d^-3 and d^-1 the test asserts.
# Both also show Kerf's addition: the part basis (dynamics/part_basis.hpp) with Jacobi scaling.
# A condition number beyond 1e16 (or infinite: a non-positive computed eigenvalue) is drawn at 1e16:
# the matrix is numerically singular there.
set terminal pngcairo size 1100,700 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
cap(k) = (k > 1e16 || k != k) ? 1e16 : k
cut(c) = (column(1) == column(1)) ? column(c) : NaN   # rows of a cut (the uncut row has x_c = NaN)
stats "conditioning_sweep.csv" every ::1::1 using 6 nooutput
uncut = STATS_min
stats "conditioning_sweep.csv" every ::1::1 using 7 nooutput
uncut_jacobi = STATS_min
set style line 1 lc rgb "#d62728" pt 7 ps 0.8 lw 1.5    # bare
set style line 2 lc rgb "#1f77b4" pt 5 ps 0.8 lw 1.5    # Jacobi
set style line 3 lc rgb "#2ca02c" pt 9 ps 0.9 lw 1.5    # Koschier
set style line 4 lc rgb "#ff7f0e" pt 6 ps 1.0 lw 1.0    # bare + eq. 22
set style line 5 lc rgb "#9467bd" pt 4 ps 1.2 lw 1.0    # Koschier + eq. 22
set style line 6 lc rgb "#17becf" pt 13 ps 0.9 lw 1.5   # part basis + Jacobi + eq. 22
set format y "10^{%L}"
set logscale y
set yrange [1:3e16]
set key top center box opaque font ",9"
set ylabel "condition number of M + {/Symbol D}t^2 K (2-norm)"

set output "conditioning_sweep.png"
set title "Five-tet cube [-1,1]^3 cut by the plane x = x_c (E = 10^6 Pa, {/Symbol n} = 0.3, {/Symbol r} = 1000 kg/m^3, {/Symbol D}t = 10^{-3} s)"
set xlabel "cut position x_c"
set xrange [-1:1]
plot "conditioning_sweep.csv" using (cut(1)):(cap(cut(6))) w lp ls 1 t "bare", \
     "" using (cut(1)):(cap(cut(7))) w lp ls 2 t "Jacobi T = diag(A)^{-1/2}", \
     "" using (cut(1)):(cap(cut(8))) w lp ls 3 t "Koschier eqs. 23-27", \
     "" using (cut(1)):(cap(cut(9))) w p ls 4 t "bare, eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (cut(1)):(cap(cut(10))) w p ls 5 t "Koschier eqs. 23-27 and eq. 22", \
     "" using (cut(1)):(cap(cut(12))) w lp ls 6 t "part basis + Jacobi, eq. 22 (Kerf)", \
     uncut w l lc rgb "#555555" dt 2 t sprintf("uncut cube (%.1f; Jacobi-scaled %.2f)", uncut, uncut_jacobi)

set output "conditioning_growth.png"
set title "The cut x = -1 + d nearing the face x = -1"
set xlabel "distance d of the cut from the face"
set logscale x
set format x "10^{%L}"
set xrange [1e-12:1] reverse
set samples 400
set key bottom left box opaque font ",9"
left(c) = (column(1) == column(1) && column(1) < 0) ? column(c) : NaN
plot "conditioning_sweep.csv" using (left(2)):(cap(left(6))) w lp ls 1 t "bare", \
     "" using (left(2)):(cap(left(7))) w lp ls 2 t "Jacobi", \
     "" using (left(2)):(cap(left(8))) w lp ls 3 t "Koschier eqs. 23-27", \
     "" using (left(2)):(cap(left(9))) w lp ls 4 t "bare, eq. 22", \
     "" using (left(2)):(cap(left(10))) w lp ls 5 t "Koschier and eq. 22", \
     "" using (left(2)):(cap(left(12))) w lp ls 6 t "part basis + Jacobi, eq. 22", \
     (x < 1e-1 && x > 3e-5 ? 6100.0 / (0.125 * x**3) : NaN) w l lc rgb "#d62728" dt 2 lw 2 t "6100 / v_{min}, v_{min} = d^3 / 8", \
     (x < 1e-2 ? 24.0 / x : NaN) w l lc rgb "#2ca02c" dt 2 lw 2 t "24 / d"
