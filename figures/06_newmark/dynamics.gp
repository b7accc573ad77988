# Chapter 6's uncut beam in time (examples/06_dynamics_study.cpp): five charts.
# modes_frequencies.png  from modes_frequencies.csv: the six lowest natural frequencies, Kerf and
#                        CalculiX *FREQUENCY, and the relative difference of omega^2;
# period_elongation.png  from period_elongation.csv: T_num / T of mode 1 under average acceleration
#                        against omega dt, measured (mode 1, tip) and the closed form;
# period_history.png     from period_history.csv: q_1 / q_s over time at omega dt = 0.2 and 1;
# energy_time.png        from energy_time.csv: where the energy goes, three integrators;
# energy_dissipation.png from energy_dissipation.csv: backward Euler's energy kept per step.
set terminal pngcairo size 1000,650 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key box opaque

set output "modes_frequencies.png"
set title "Clamped Tet10 beam 0.03 x 0.06 x 0.2 m (3 x 6 x 20 cells): the six lowest natural frequencies"
set xlabel "mode"
set ylabel "frequency (Hz)"
set y2label "relative difference of {/Symbol w}^2, CalculiX - Kerf"
set logscale y2
set format y2 "10^{%L}"
set y2tics
set ytics nomirror
set xrange [0.5:6.5]
set key top left
plot "modes_frequencies.csv" using 1:3 every ::1 w p pt 7 ps 1.6 lc rgb "#1f77b4" t "Kerf (subspace iteration, exact mass)", \
     "" using 1:5 every ::1 w p pt 6 ps 2.4 lc rgb "#d62728" t "CalculiX *FREQUENCY (ARPACK)", \
     "" using 1:6 every ::1 axes x1y2 w lp pt 4 lc rgb "#555555" dt 2 t "relative difference (right axis)"
unset logscale y2
unset y2tics
unset y2label
set ytics mirror
set format y2

set output "period_elongation.png"
set title "Average acceleration Newmark: the first mode's period against the step (beam under sudden gravity)"
set xlabel "{/Symbol w}_1 {/Symbol D}t"
set ylabel "T_{num} / T"
set logscale x
set xrange [0.04:4]
set key top left
set samples 200
plot x / (2 * atan(x / 2)) w l lc rgb "#2ca02c" lw 2 t "closed form {/Symbol w}{/Symbol D}t / (2 atan({/Symbol w}{/Symbol D}t / 2))", \
     "period_elongation.csv" using 1:7 every ::1 w p pt 7 ps 1.4 lc rgb "#1f77b4" t "measured: mode 1 (q_1 = {/Symbol f}_1^T M u)", \
     "" using 1:8 every ::1 w p pt 6 ps 1.8 lc rgb "#d62728" t "measured: tip u_x crossings of its static value"
unset logscale x

set output "period_history.png"
set title "q_1 / q_s under sudden gravity: Newmark's samples on 1 - cos(n 2 atan({/Symbol w}{/Symbol D}t/2)), beside the exact 1 - cos({/Symbol w} t)"
set xlabel "t (s)"
set ylabel "q_1 / q_s"
set xrange [0:*]
set key bottom right
pick(w, c) = (column(1) == w) ? column(c) : NaN
stats "period_elongation.csv" every ::1::1 using 4 nooutput
T1 = STATS_min
plot 1 - cos(2 * pi * x / T1) w l lc rgb "#999999" dt 2 t "exact 1 - cos({/Symbol w}_1 t)", \
     "period_history.csv" using (pick(0.2, 2)):(pick(0.2, 3)) w lp pt 7 ps 0.6 lc rgb "#1f77b4" t "Newmark, {/Symbol w}{/Symbol D}t = 0.2", \
     "" using (pick(1.0, 2)):(pick(1.0, 3)) w lp pt 5 ps 0.9 lc rgb "#d62728" t "Newmark, {/Symbol w}{/Symbol D}t = 1", \
     "" using (pick(1.0, 2)):(pick(1.0, 4)) w p pt 6 ps 1.6 lc rgb "#2ca02c" t "closed form, {/Symbol w}{/Symbol D}t = 1"

set output "energy_time.png"
set terminal pngcairo size 1500,500 enhanced font "DejaVu Sans,10" linewidth 1.5
set multiplot layout 1,3 title "Energy of the beam under sudden gravity, {/Symbol D}t = T_1 / 40 (J)"
run(r, c) = (strcol(1) eq r) ? column(c) : NaN
do for [r in "newmark newmark_rayleigh backward_euler"] {
  set title (r eq "newmark" ? "average acceleration, undamped" : (r eq "newmark_rayleigh" ? "average acceleration, Rayleigh {/Symbol x} = 0.05 (modes 1, 2)" : "backward Euler, undamped"))
  set xlabel "t (s)"
  set ylabel "J"
  set key top left font ",8"
  set y2label "|balance drift| (J)"
  set logscale y2
  set format y2 "10^{%L}"
  set y2range [1e-18:1e-10]
  set y2tics
  set ytics nomirror
  plot "energy_time.csv" using (run(r, 3)):(run(r, 4)) w l lc rgb "#1f77b4" t "kinetic", \
       "" using (run(r, 3)):(run(r, 5)) w l lc rgb "#ff7f0e" t "elastic", \
       "" using (run(r, 3)):(run(r, 6)) w l lc rgb "#000000" t "external work", \
       "" using (run(r, 3)):(run(r, 7) + run(r, 8)) w l lc rgb "#d62728" t "dissipated (damping + numerical)", \
       "" using (run(r, 3)):(abs(run(r, 9))) axes x1y2 w l lc rgb "#999999" t "|balance drift| (right)"
}
unset multiplot
unset logscale y2
unset y2tics
unset y2label
set ytics mirror

set terminal pngcairo size 1000,650 enhanced font "DejaVu Sans,11" linewidth 1.5
set output "energy_dissipation.png"
set title "Backward Euler's numerical damping: the energy mode 1 keeps per step, free vibration"
set xlabel "{/Symbol w}_1 {/Symbol D}t"
set ylabel "E_{n+1} / E_n"
set logscale x
set xrange [0.008:12]
set yrange [0:1.05]
set key bottom left
plot 1 / (1 + x**2) w l lc rgb "#2ca02c" lw 2 t "closed form 1 / (1 + {/Symbol w}^2{/Symbol D}t^2) = {/Symbol r}^2", \
     "energy_dissipation.csv" using 1:4 every ::1 w p pt 7 ps 1.4 lc rgb "#1f77b4" t "measured (10 steps)", \
     1 w l lc rgb "#999999" dt 2 t "average acceleration Newmark: 1"
