#!/bin/sh
# Regenerates chapter 2's benchmark report and its time-accuracy chart: runs bench_corotation
# on one core (a few minutes), keeps its report (bench_corotation.md) and the table of its
# quasi-static solves (bench_corotation.csv) here, and draws solve_speed.png from the table.
#
#   figures/02_corotation/make_bench_figure.sh [BUILD_DIR]     (default: build/release)
#
# Run it on a quiet machine: the report's numbers are wall times.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
cmake --build "$build" --target bench_corotation > /dev/null
command -v gnuplot > /dev/null || { echo "make_bench_figure.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/bench_corotation" --out "$here/bench_corotation.md"
cd "$here"
gnuplot solve_speed.gp
echo "wrote $here/bench_corotation.md, bench_corotation.csv and solve_speed.png"
