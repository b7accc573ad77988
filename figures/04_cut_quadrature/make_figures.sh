#!/bin/sh
# Regenerates chapter 4's measured results: builds and runs the quadrature study (Koschier's
# Table 1 again; a few minutes on an idle machine, most of it the finest spheres sampled on
# the finest grids), keeps its CSV files, its markdown table and its printed summary here (they
# are committed data) and draws the error-vs-cost chart from cost.csv with gnuplot.
#
#   figures/04_cut_quadrature/make_figures.sh [BUILD_DIR]     (default: build/release)
#
# The timings are one-core timings on whatever else the machine is doing: best of >= 3 runs.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 04_quadrature_study
study="$build/bin/04_quadrature_study"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" | tee "$out/study_stdout.txt"
for file in table1.csv cost.csv table1.md study_stdout.txt; do cp "$out/$file" "$here/$file"; done

cd "$here"
gnuplot error_cost.gp
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
