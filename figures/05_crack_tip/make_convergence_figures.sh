#!/bin/sh
# Regenerates chapter 5's convergence study: builds and runs 05_convergence_study (Williams's
# field on the boundary of a cracked slab; errors over a mesh ladder without branch functions,
# with topological and with geometric enrichment; K by the interaction integral; the enrichment
# radius against cost; several minutes on one core), keeps its CSV and printed rows here
# (committed data) and draws the chart with gnuplot.
#
#   figures/05_crack_tip/make_convergence_figures.sh [BUILD_DIR]   (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_convergence_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cmake --build "$build" -j1 --target 05_convergence_study
"$build/bin/05_convergence_study" --out "$out" | tee "$out/convergence_stdout.txt"
for file in convergence.csv convergence_stdout.txt; do cp "$out/$file" "$here/$file"; done
(cd "$here" && gnuplot convergence.gp)
echo "wrote $here/convergence.png"
