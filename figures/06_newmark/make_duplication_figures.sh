#!/bin/sh
# Regenerates chapter 6's Koschier Figs. 11-12 (XFEM against element duplication): builds and
# runs the cut dynamics study's parts slab and unfold (a few minutes), keeps their CSV files and
# printed summary here (committed data) and draws slab_drop.png and unfold_com.png.
#
#   figures/06_newmark/make_duplication_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_duplication_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_cut_dynamics_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/06_cut_dynamics_study" --only slab,unfold --out "$out" | tee "$out/duplication_stdout.txt"
for file in slab.csv unfold.csv unfold_history.csv duplication_stdout.txt; do
  cp "$out/$file" "$here/$file"
done

cd "$here"
gnuplot duplication.gp
echo "wrote $here/slab_drop.png $here/unfold_com.png"
