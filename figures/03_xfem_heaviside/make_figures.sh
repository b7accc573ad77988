#!/bin/sh
# Regenerates chapter 3's measured results: runs the full XFEM study (a few minutes: the
# corotated Tet10 reference and the CalculiX runs take most of it), keeps its CSV files and its
# printed summary here (they are committed data: the tables of chapters/03_xfem_heaviside/results.md
# are copied from them) and draws the PNG figures from them with gnuplot.
#
#   figures/03_xfem_heaviside/make_figures.sh [BUILD_DIR]     (default: build/release)
#
# The timings are one-core timings: we pin OpenBLAS (CHOLMOD's BLAS) and OpenMP (CalculiX) to a
# single thread. The benchmark behind the chapter's speed table is separate:
# cmake --build BUILD_DIR --target bench.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
study="$build/bin/03_xfem_study"
if [ ! -x "$study" ]; then
  echo "make_figures.sh: $study not found; build it first: cmake --build $build --target 03_xfem_study" >&2
  exit 1
fi
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" | tee "$out/study_stdout.txt"
for csv in ladder.csv reference.csv fraction.csv fraction_uncut.csv section.csv; do
  cp "$out/$csv" "$here/$csv"
done
cp "$out/study_stdout.txt" "$here/study_stdout.txt"

cd "$here"
gnuplot ladder_dofs.gp
gnuplot ladder_time.gp
gnuplot fraction.gp
gnuplot section.gp
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
