#!/bin/sh
# Regenerates chapter 6's uncut-beam results: builds and runs the dynamics study (natural
# frequencies against CalculiX *FREQUENCY, Newmark's period elongation, the energy account;
# a minute or two), keeps its CSV files and printed summary here (they are committed data) and
# draws the modes_, period_ and energy_ charts with gnuplot. CalculiX comes from the build's
# KERF_CCX (without it the CalculiX column is NaN).
#
#   figures/06_newmark/make_dynamics_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_dynamics_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_dynamics_study

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/06_dynamics_study" --out "$out" | tee "$out/modes_period_energy_stdout.txt"
for file in modes_frequencies.csv period_elongation.csv period_history.csv energy_time.csv energy_dissipation.csv modes_period_energy_stdout.txt; do
  cp "$out/$file" "$here/$file"
done

cd "$here"
gnuplot dynamics.gp
echo "wrote $here/modes_frequencies.png $here/period_elongation.png $here/period_history.png $here/energy_time.png $here/energy_dissipation.png"
