# Chapter 2's quasi-static solve of the 10k-tet beam: time against accuracy, one point per
# configuration of bench_corotation (d). Data: bench_corotation.csv, written by
#   OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 bench_corotation --out figures/02_corotation/bench_corotation.md
load "common.gp"
set output "solve_speed.png"
set size ratio 0
set logscale xy
set format y "10^{%L}"
set xlabel "wall time of the whole solve (s), one core"
set ylabel "max_v |u - u_{ref}| / max_v |u_{ref}|  (u_{ref}: Newton to 10^{-12})"
set title "Corotated Tet4 beam, 6534 unknowns, tip load 1.4 N: time against accuracy" font ",13"
set key outside right top box font ",10"
set yrange [1e-17:1e-2]
at_least_eps(e) = e < 1e-16 ? 1e-16 : e
# Columns: 1 tangent, 2 predictor, 3 Newton tolerance, 4 solver, 5 load steps, 10 seconds, 12 error.
row(tangent, predictor, solver) = strcol(1) eq tangent && strcol(2) eq predictor && strcol(4) eq solver
label(c) = sprintf("%d steps, %.0e", int(column(5)), column(3))
plot "bench_corotation.csv" using (row("consistent", "previous", "cholmod") ? $10 : NaN):(at_least_eps($12)) w p ls 1 ps 1.6 t "consistent, last equilibrium, CHOLMOD", \
     "" using (row("warped", "previous", "cholmod") ? $10 : NaN):(at_least_eps($12)) w p ls 2 ps 1.6 t "warped, last equilibrium, CHOLMOD", \
     "" using (row("consistent", "previous", "cg-ichol") ? $10 : NaN):(at_least_eps($12)) w p ls 6 ps 1.6 t "consistent, last equilibrium, CG-IChol", \
     "" using (row("consistent", "secant", "cholmod") ? $10 : NaN):(at_least_eps($12)) w p ls 5 ps 1.6 t "consistent, secant, CHOLMOD", \
     "" using (row("consistent", "secant", "cg-cholmod") ? $10 : NaN):(at_least_eps($12)) w p ls 3 ps 1.6 t "consistent, secant, CG + reused CHOLMOD", \
     "" using 10:(at_least_eps($12)):(label(0)) w labels offset 0.6,0.7 left font ",8" tc rgb "#555555" notitle
