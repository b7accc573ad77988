#!/bin/sh
# Regenerates chapter 6's conditioning results (Koschier's Fig. 14 again): builds and runs the
# conditioning study (the five-tet cube cut by x = x_c; about a second), keeps its CSV files and
# printed summary here (they are committed data) and draws conditioning_sweep.png and
# conditioning_growth.png with gnuplot.
#
#   figures/06_newmark/make_conditioning_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_conditioning_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_conditioning_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/06_conditioning_study" --out "$out" | tee "$out/conditioning_stdout.txt"
for file in conditioning_sweep.csv conditioning_slopes.csv conditioning_stdout.txt; do cp "$out/$file" "$here/$file"; done

cd "$here"
gnuplot conditioning.gp
echo "wrote $here/conditioning_sweep.png $here/conditioning_growth.png"
