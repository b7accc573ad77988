#!/bin/sh
# Regenerates chapter 6's energy chart from real runs of the chapter's program: the demo (the
# beam whose cut flap folds over its strip; corotational, rotations frozen per step), the same
# scene with Newton to convergence in every step, and linear XFEM (examples/06_flap_linear.json).
# Keeps each run's energy.csv and the history of two probes (probes.csv: the flap's free end
# and the beam just below the cut) here (committed data) with its printed summary, and draws
# energy.png and flap_tip.png with gnuplot.
#
#   figures/06_newmark/make_figures.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_newmark
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
run() { # name, then the program's arguments
  name=$1
  shift
  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 "$build/bin/06_newmark" --out "$out/$name" \
    --probes "$here/probes.csv" --probes-history "$here/history_$name.csv" "$@" | tee "$here/${name}_stdout.txt"
  cp "$out/$name/energy.csv" "$here/energy_$name.csv"
}
run demo_frozen
# The demo scene with Newton per step: the program prints its demo scene nowhere, so we make
# the same scene from the linear example (they differ in "model" and "name" only).
sed -e 's/"model": "linear"/"model": "corotational"/' -e 's/"name": "flap_linear"/"name": "flap_newton"/' \
    -e 's/"rayleigh": \[3, 0.002\]/"rayleigh": [3, 0.002], "corotation": "newton"/' \
    "$root/examples/06_flap_linear.json" > "$out/flap_newton.json"
run demo_newton --scene "$out/flap_newton.json"
run flap_linear --scene "$root/examples/06_flap_linear.json"
(cd "$here" && gnuplot energy.gp && gnuplot flap_tip.gp)
echo "wrote $here/energy.png and $here/flap_tip.png"
