#!/bin/sh
# Regenerates chapter 2's measured results: runs the full corotation study (a few minutes: the
# Tet10 solves and the CalculiX NLGEOM runs take most of it), keeps its CSV files and its
# printed summary here (they are committed data: the tables of chapters/02_corotation/results.md
# are copied from them) and draws the PNG figures from them with gnuplot.
#
#   figures/02_corotation/make_figures.sh [BUILD_DIR]     (default: build/release)
#
# The timings are one-core timings: we pin OpenBLAS (CHOLMOD's BLAS) and OpenMP (CalculiX) to a
# single thread, so that Kerf and CalculiX are compared on equal terms. The benchmark behind the
# chapter's speed table is separate: cmake --build BUILD_DIR --target bench.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
study="$build/bin/02_corotation_study"
if [ ! -x "$study" ]; then
  echo "make_figures.sh: $study not found; build it first: cmake --build $build --target 02_corotation_study" >&2
  exit 1
fi
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" | tee "$out/study_stdout.txt"
for csv in ghost.csv load.csv inversion.csv block.csv; do
  cp "$out/$csv" "$here/$csv"
done
cp "$out/study_stdout.txt" "$here/study_stdout.txt"

cd "$here"
gnuplot ghost.gp
gnuplot deflection.gp
gnuplot error.gp
gnuplot inversion.gp
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
