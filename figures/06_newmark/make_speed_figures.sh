#!/bin/sh
# Regenerates chapter 6's speed benchmark and its two charts: runs bench_newmark on one core
# (several minutes: the 100k-tet block with CHOLMOD takes the longest), keeps its report as
# bench_newmark_run.md and its table as speed_bench.csv here, and draws from the table
#   speed_ms_per_step.png   ms per step against tets, one line per solver strategy;
#   speed_error_cost.png    error after 20 steps against ms per step (accuracy against cost).
#
#   figures/06_newmark/make_speed_figures.sh [BUILD_DIR]     (default: build/release)
#   figures/06_newmark/make_speed_figures.sh --charts        (only redraw from speed_bench.csv)
#
# Run it on a quiet machine: the numbers are wall times.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
command -v gnuplot > /dev/null || { echo "make_speed_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
if [ "${1:-}" != "--charts" ]; then
  build=${1:-$root/build/release}
  cmake --build "$build" --target bench_newmark > /dev/null
  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/bench_newmark" --out "$here/bench_newmark_run.md"
  mv "$here/bench_newmark_run.csv" "$here/speed_bench.csv"
fi
cd "$here"
gnuplot speed.gp
echo "wrote $here/speed_bench.csv, speed_ms_per_step.png and speed_error_cost.png"
