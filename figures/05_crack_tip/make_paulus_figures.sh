#!/bin/sh
# Paulus's Fig. 9, the front sweep and the partial cuts (paulus.md, sweep.md, partial.md): runs
# the study into this folder, then the charts. From the repository root:
#   sh figures/05_crack_tip/make_paulus_figures.sh [build/release]
set -e
build=${1:-build/release}
here=$(dirname "$0")
"$build/bin/05_paulus_study" --out "$here" | tee "$here/paulus_stdout.txt"
cd "$here"
gnuplot paulus.gp
gnuplot sweep.gp
gnuplot partial.gp
