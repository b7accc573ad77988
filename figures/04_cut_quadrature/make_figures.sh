#!/bin/sh
# Regenerates chapter 4's measured results: builds and runs the quadrature study (Koschier's
# Table 1 again; a few minutes on an idle machine, most of it the finest spheres sampled on
# the finest grids) and the curved-cut study (the beam cut clean through by a dome and a ridge,
# XFEM against conforming ladders; some 20 minutes, most of it the two Tet10 references and the
# finest Tet10 XFEM meshes), keeps their CSV files, markdown table and printed summaries here
# (they are committed data) and draws the charts with gnuplot.
#
#   figures/04_cut_quadrature/make_figures.sh [BUILD_DIR] [PART]   (default: build/release, all)
#
# PART is "table1" or "curved" to run one study only.
#
# The timings are one-core timings on whatever else the machine is doing: best of >= 3 runs.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
part=${2:-all}
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

if [ "$part" = all ] || [ "$part" = table1 ]; then
  cmake --build "$build" -j1 --target 04_quadrature_study
  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/04_quadrature_study" --out "$out" | tee "$out/study_stdout.txt"
  for file in table1.csv cost.csv table1.md study_stdout.txt; do cp "$out/$file" "$here/$file"; done
  (cd "$here" && gnuplot error_cost.gp)
fi
if [ "$part" = all ] || [ "$part" = curved ]; then
  cmake --build "$build" -j1 --target 04_curved_cut_study
  OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/04_curved_cut_study" --out "$out" | tee "$out/curved_stdout.txt"
  for file in curved_ladder.csv curved_reference.csv curved_factor.csv curved_stdout.txt; do cp "$out/$file" "$here/$file"; done
  (cd "$here" && gnuplot curved_ladder.gp && gnuplot curved_rules.gp)
fi
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
