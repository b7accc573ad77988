#!/bin/sh
# Regenerates chapter 6's validation results of the cut body in time: builds and runs the cut
# dynamics study (Schoch's falling slice, Koschier's hinged cubes, frozen rotations against
# Newton, the central difference above its critical step; three or four minutes, most of it
# the Newton reference run at dt = 0.625 ms), keeps its CSV files and printed summary here
# (they are committed data) and draws the slice_, hinge_, rotations_ and explicit_ charts
# (the study's parts slab and unfold are make_duplication_figures.sh's).
#
#   figures/06_newmark/make_validation_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_validation_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_cut_dynamics_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/06_cut_dynamics_study" --only slice,hinge,rotations,explicit --out "$out" | tee "$out/cut_dynamics_stdout.txt"
for file in slice_history.csv hinge.csv rotations.csv explicit.csv explicit_growth.csv cut_dynamics_stdout.txt; do
  cp "$out/$file" "$here/$file"
done

cd "$here"
gnuplot validation.gp
echo "wrote $here/slice_swing.png $here/hinge_offset.png $here/rotations_cost.png $here/explicit_blowup.png"
