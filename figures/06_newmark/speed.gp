# Chapter 6's speed benchmark (bench_newmark): the corotational cut soft block, one core.
# Data: speed_bench.csv, written by make_speed_figures.sh. Columns: 1 tets, 3 unknowns,
# 4 strategy, 5 solver type, 6 CG tolerance, 8 ms per step, 16 relative error after the run.
set terminal pngcairo size 1100,520 enhanced font "DejaVu Sans,11" linewidth 1.5
set datafile separator ","
set datafile missing NaN
set grid xtics ytics mxtics mytics lc rgb "#dddddd"
set key outside right top box font ",10"
set logscale xy
set xrange [1000:150000]
at_least(e) = e < 1e-16 ? 1e-16 : e
is(s) = strcol(4) eq s

set output "speed_ms_per_step.png"
set xlabel "tets"
set ylabel "processor time per step (ms), one core"
set title "Corotational cut soft block, Newmark dt = 10 ms, frozen rotations: cost of a step" font ",13"
set format y "10^{%L}"
plot "speed_bench.csv" using (is("cholmod") ? $1 : NaN):8 w lp lc rgb "#000000" pt 7 t "CHOLMOD every step", \
     "" using (is("cg-jacobi 1e-02") ? $1 : NaN):8 w lp lc rgb "#17becf" pt 4 t "CG-Jacobi 1e-2", \
     "" using (is("cg-jacobi 1e-03") ? $1 : NaN):8 w lp lc rgb "#1f77b4" pt 5 lw 3 t "CG-Jacobi 1e-3 (the default)", \
     "" using (is("cg-ichol 1e-03") ? $1 : NaN):8 w lp lc rgb "#2ca02c" pt 9 t "CG-IChol 1e-3", \
     "" using (is("cg-cholmod 1e-02") ? $1 : NaN):8 w lp lc rgb "#9467bd" pt 15 t "CG + reused CHOLMOD 1e-2", \
     "" using (is("cg-cholmod 1e-03") ? $1 : NaN):8 w lp lc rgb "#d62728" pt 13 t "CG + reused CHOLMOD 1e-3", \
     "" using 1:(is("cg-jacobi 1e-03") ? $9 : NaN) w lp lc rgb "#1f77b4" pt 1 dt 2 t "its assembly phase alone", \
     10 * x / 10000 w l lc rgb "#777777" dt 3 t "goal: 10 ms at 10k, 100 ms at 100k"

set output "speed_error_cost.png"
set autoscale x
set xlabel "processor time per step (ms), one core"
set ylabel "|u - u_{ref}| / |u_{ref}| after 20 steps"
set title "The 10k-tet block (10368 tets): accuracy against cost (labels: CG tolerance)" font ",13"
set format y "10^{%L}"
set yrange [1e-13:1]
ten_k(type) = (strcol(5) eq type && $1 > 5000 && $1 < 20000)
plot "speed_bench.csv" using (ten_k("cg-jacobi") ? $8 : NaN):(at_least($16)) w lp lc rgb "#1f77b4" pt 5 t "CG-Jacobi", \
     "" using (ten_k("cg-ichol") ? $8 : NaN):(at_least($16)) w lp lc rgb "#2ca02c" pt 9 t "CG-IChol", \
     "" using (ten_k("cg-cholmod") ? $8 : NaN):(at_least($16)) w lp lc rgb "#d62728" pt 13 t "CG + reused CHOLMOD", \
     "" using (ten_k("cholmod") ? $8 : NaN):(1e-12) w p lc rgb "#000000" pt 7 ps 1.5 t "CHOLMOD (the reference, error 0)", \
     "" using (strcol(5) ne "cholmod" && $1 > 5000 && $1 < 20000 ? $8 : NaN):(at_least($16)):(sprintf("%.0e", $6)) w labels offset 0.5,0.6 left font ",8" tc rgb "#555555" notitle, \
     0.01 w l lc rgb "#777777" dt 3 t "goal: 1 %"
