#!/bin/sh
# Regenerates chapter 1's measured results: runs the full beam study (a few minutes), keeps its
# CSV files here (they are committed data: the tables of chapters/01_linear_fem/results.md are
# copied from them) and draws the PNG figures from them with gnuplot.
#
#   figures/01_linear_fem/make_figures.sh [BUILD_DIR] [PARTS]     (default: build/release, all parts)
#
# PARTS, comma-separated, runs only some parts of the study (01_beam_study --only PARTS) and
# replaces only their files here: ladder (ladder.csv, reference.csv), locking (locking.csv),
# calculix (calculix.csv). study_stdout.txt is replaced by the run's printed summary, or, for
# some parts only, kept as study_stdout_PARTS.txt beside it.
#
# The timings are one-core timings: we pin OpenBLAS (CHOLMOD's BLAS) and OpenMP (CalculiX) to a
# single thread, so that Kerf and CalculiX are compared on equal terms.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
parts=${2:-ladder,locking,calculix}
study="$build/bin/01_beam_study"
if [ ! -x "$study" ]; then
  echo "make_figures.sh: $study not found; build it first: cmake --build $build --target 01_beam_study" >&2
  exit 1
fi
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" --only "$parts" | tee "$out/study_stdout.txt"
for csv in ladder.csv reference.csv locking.csv calculix.csv; do
  if [ -f "$out/$csv" ]; then cp "$out/$csv" "$here/$csv"; fi
done
if [ "$parts" = "ladder,locking,calculix" ]; then
  cp "$out/study_stdout.txt" "$here/study_stdout.txt"
else
  cp "$out/study_stdout.txt" "$here/study_stdout_$(echo "$parts" | tr ',' '_').txt"
fi

cd "$here"
gnuplot error_vs_dofs.gp
gnuplot error_vs_time.gp
gnuplot locking.gp
if [ -f calculix.csv ]; then gnuplot kerf_vs_calculix.gp; fi
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
