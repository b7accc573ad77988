#!/bin/sh
# Regenerates chapter 1's measured results: runs the full beam study (a few minutes), keeps its
# CSV files here (they are committed data: the tables of chapters/01_linear_fem/results.md are
# copied from them) and draws the PNG figures from them with gnuplot.
#
#   figures/01_linear_fem/make_figures.sh [BUILD_DIR]     (default: build/release)
#
# The timings are one-core timings: we pin OpenBLAS (CHOLMOD's BLAS) and OpenMP (CalculiX) to a
# single thread, so that Kerf and CalculiX are compared on equal terms.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
study="$build/bin/01_beam_study"
if [ ! -x "$study" ]; then
  echo "make_figures.sh: $study not found; build it first: cmake --build $build --target 01_beam_study" >&2
  exit 1
fi
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" | tee "$out/study_stdout.txt"
for csv in ladder.csv reference.csv locking.csv calculix.csv; do
  [ -f "$out/$csv" ] && cp "$out/$csv" "$here/$csv"
done
cp "$out/study_stdout.txt" "$here/study_stdout.txt"

cd "$here"
gnuplot error_vs_dofs.gp
gnuplot error_vs_time.gp
gnuplot locking.gp
[ -f calculix.csv ] && gnuplot kerf_vs_calculix.gp
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
