#!/bin/sh
# Regenerates chapter 5's opening study: builds and runs 05_opening_study (the demo's crack-mouth
# opening under its edge forces on conforming and XFEM mesh ladders, extrapolated to a reference;
# the prescribed edge displacement, whose force has no limit; about 15 minutes on one loaded core,
# 6 GB), keeps its CSV files and printed rows here (committed data) and draws the chart.
#
#   figures/05_crack_tip/make_opening_figures.sh [BUILD_DIR]   (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_opening_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cmake --build "$build" -j1 --target 05_opening_study
"$build/bin/05_opening_study" --out "$out" | tee "$out/opening_stdout.txt"
for file in opening.csv opening_limits.csv opening_reference.csv opening_stdout.txt; do cp "$out/$file" "$here/$file"; done
(cd "$here" && gnuplot opening.gp)
echo "wrote $here/opening.png"
