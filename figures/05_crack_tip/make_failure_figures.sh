#!/bin/sh
# Regenerates chapter 5's failure study: builds and runs 05_failure_study (the condition number
# of K_ff with branch DOFs against the enrichment radius and the front's distance to a node and
# to a face; dense eigenvalues, about a minute), keeps its CSVs and printed summary here
# (committed data) and draws the chart with gnuplot.
#
#   figures/05_crack_tip/make_failure_figures.sh [BUILD_DIR]   (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_failure_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cmake --build "$build" -j1 --target 05_failure_study
"$build/bin/05_failure_study" --out "$out" | tee "$out/failures_stdout.txt"
for file in failures.csv failures_slopes.csv failures_stdout.txt; do cp "$out/$file" "$here/$file"; done
(cd "$here" && gnuplot failures.gp)
echo "wrote $here/failures.png"
