#!/bin/sh
# Regenerates the measured results of chapter 4's "Where it fails": builds and runs the failure
# study (slivers with every rule, cuts along mesh faces, cuts a hair short of the surface, the
# sign of a point near a kink; about a minute of computing, most of it the dense eigenvalues of
# the sliver sweep), keeps its CSV files and its printed summary here (they are committed data;
# the summary with the solves the library refuses, which the study reports on stderr, each beside
# its row) and draws failure_fraction.png and failure_kink.png with gnuplot.
#
#   figures/04_cut_quadrature/make_failure_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_failure_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 04_failure_study
study="$build/bin/04_failure_study"

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 stdbuf -oL "$study" --out "$out" 2>&1 | tee "$out/failure_stdout.txt"
for file in failure_fraction.csv failure_faces.csv failure_gap.csv failure_kink.csv failure_stdout.txt; do cp "$out/$file" "$here/$file"; done

cd "$here"
gnuplot failure.gp
echo "wrote $here/failure_fraction.png $here/failure_kink.png"
