# Koschier's Fig. 14 again (examples/06_conditioning_study.cpp), two charts from conditioning_sweep.csv:
# conditioning_sweep.png: the 2-norm condition number of A = M + dt^2 K of the five-tet cube
# [-1, 1]^3 against the cut position x_c (semi-log, as the paper's figure), the paper's variants,
# and the uncut cube's as a line;
# conditioning_growth.png: the same against the distance d of the cut from the face it nears
# (log-log, the cut nearing x = -1), with the slopes d^-3 and d^-1 the test asserts.
# Both also show Jacobi scaling after eq. 22 tested on every part of a support (the home slab
# of the face's nodes held once its relative volume 1.5 d is below epsilon), with Koschier's
# epsilon = 1e-9 and with 1e-3, and Kerf's part basis (dynamics/part_basis.hpp) with Jacobi scaling.
# A condition number beyond 1e16 (or infinite: a non-positive computed eigenvalue) is drawn at 1e16:
# the matrix is numerically singular there.
# Columns: 1 x_c, 2 d, 6 plain, 7 jacobi, 8 koschier, 9 plain_constrained, 10 koschier_constrained,
# 12 part_jacobi_constrained, 13 jacobi_constrained, 16 jacobi_constrained_1e-3.
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
set style line 7 lc rgb "#8c564b" pt 3 ps 1.0 lw 1.5    # Jacobi + eq. 22 on every part, epsilon = 1e-9
set style line 8 lc rgb "#e377c2" pt 2 ps 1.0 lw 1.5    # Jacobi + eq. 22 on every part, epsilon = 1e-3
set format y "10^{%L}"
set logscale y
set yrange [1:3e16]
set key top center box opaque font ",9"
set ylabel "condition number of M + {/Symbol D}t^2 K (2-norm)"

set output "conditioning_sweep.png"
set title "Five-tet cube [-1,1]^3 cut by the plane x = x_c (E = 10^6 Pa, {/Symbol n} = 0.3, {/Symbol r} = 1000 kg/m^3, {/Symbol D}t = 10^{-3} s; eq. 22 on every part)"
set xlabel "cut position x_c"
set xrange [-1:1]
plot "conditioning_sweep.csv" using (cut(1)):(cap(cut(6))) w lp ls 1 t "bare", \
     "" using (cut(1)):(cap(cut(7))) w lp ls 2 t "Jacobi T = diag(A)^{-1/2}", \
     "" using (cut(1)):(cap(cut(8))) w lp ls 3 t "Koschier eqs. 23-27", \
     "" using (cut(1)):(cap(cut(9))) w p ls 4 t "bare, eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (cut(1)):(cap(cut(10))) w p ls 5 t "Koschier eqs. 23-27 and eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (cut(1)):(cap(cut(13))) w p ls 7 t "Jacobi, eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (cut(1)):(cap(cut(16))) w p ls 8 t "Jacobi, eq. 22 ({/Symbol e} = 10^{-3})", \
     "" using (cut(1)):(cap(cut(12))) w lp ls 6 t "part basis + Jacobi, eq. 22 ({/Symbol e} = 10^{-9}; Kerf)", \
     uncut w l lc rgb "#555555" dt 2 t sprintf("uncut cube (%.1f; Jacobi-scaled %.2f)", uncut, uncut_jacobi)

# Wider, the key outside: inside, it would hide the curves that stay at the uncut cube's value.
set terminal pngcairo size 1400,700 enhanced font "DejaVu Sans,11" linewidth 1.5
set output "conditioning_growth.png"
set title "The cut x = -1 + d nearing the face x = -1 (eq. 22 tests every part of a support, the home part too)"
set xlabel "distance d of the cut from the face"
set logscale x
set format x "10^{%L}"
set xrange [1e-12:1] reverse
set samples 400
set key outside right center box opaque font ",9"
left(c) = (column(1) == column(1) && column(1) < 0) ? column(c) : NaN
# Where eq. 22 holds the face's home slabs (relative volume 1.5 d at the odd corners): d = epsilon / 1.5.
set arrow 1 from 1e-3 / 1.5, graph 0 to 1e-3 / 1.5, graph 1 nohead lc rgb "#e377c2" dt 3
set arrow 2 from 1e-9 / 1.5, graph 0 to 1e-9 / 1.5, graph 1 nohead lc rgb "#8c564b" dt 3
set label 1 "1.5 d = {/Symbol e} = 10^{-3}" at 1e-3 / 1.5, 1e11 right offset -0.5, 0 tc rgb "#e377c2" font ",9"
set label 2 "1.5 d = {/Symbol e} = 10^{-9}" at 1e-9 / 1.5, 1e13 right offset -0.5, 0 tc rgb "#8c564b" font ",9"
plot "conditioning_sweep.csv" using (left(2)):(cap(left(6))) w lp ls 1 t "bare", \
     "" using (left(2)):(cap(left(7))) w lp ls 2 t "Jacobi", \
     "" using (left(2)):(cap(left(8))) w lp ls 3 t "Koschier eqs. 23-27", \
     "" using (left(2)):(cap(left(9))) w lp ls 4 t "bare, eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (left(2)):(cap(left(10))) w lp ls 5 t "Koschier and eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (left(2)):(cap(left(13))) w lp ls 7 t "Jacobi, eq. 22 ({/Symbol e} = 10^{-9})", \
     "" using (left(2)):(cap(left(16))) w lp ls 8 t "Jacobi, eq. 22 ({/Symbol e} = 10^{-3})", \
     "" using (left(2)):(cap(left(12))) w lp ls 6 t "part basis + Jacobi, eq. 22 ({/Symbol e} = 10^{-9})", \
     (x < 1e-1 && x > 3e-5 ? 6100.0 / (0.125 * x**3) : NaN) w l lc rgb "#d62728" dt 2 lw 2 t "6100 / v_{min}, v_{min} = d^3 / 8", \
     (x < 1e-2 ? 24.0 / x : NaN) w l lc rgb "#2ca02c" dt 2 lw 2 t "24 / d", \
     uncut_jacobi w l lc rgb "#555555" dt 2 t sprintf("uncut cube, Jacobi-scaled (%.2f)", uncut_jacobi)
