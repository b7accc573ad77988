#!/bin/sh
# Regenerates chapter 5's quadrature study: builds and runs 05_front_quadrature_study (the
# crack-tip integrands over a tet the front crosses and one it grazes; refined sub-tets against
# the collapsed rule; a few seconds), keeps its CSV and printed summary here (committed data) and
# draws the chart with gnuplot.
#
#   figures/05_crack_tip/make_quadrature_figures.sh [BUILD_DIR]   (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_quadrature_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cmake --build "$build" -j1 --target 05_front_quadrature_study
"$build/bin/05_front_quadrature_study" --out "$out" | tee "$out/front_quadrature_stdout.txt"
for file in front_quadrature.csv front_quadrature_stdout.txt; do cp "$out/$file" "$here/$file"; done
(cd "$here" && gnuplot front_quadrature.gp)
echo "wrote $here/front_quadrature.png"
