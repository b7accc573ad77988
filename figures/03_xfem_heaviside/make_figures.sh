#!/bin/sh
# Regenerates chapter 3's measured results: runs the full XFEM study (a few minutes on an idle
# machine: the corotated Tet10 reference and the CalculiX runs take most of it), keeps its CSV files and its
# printed summary here (they are committed data: the tables of chapters/03_xfem_heaviside/results.md
# are copied from them) and draws the PNG figures from them with gnuplot.
#
#   figures/03_xfem_heaviside/make_figures.sh [BUILD_DIR] [PARTS]     (default: build/release, all parts)
#
# PARTS, comma-separated, runs only some parts of the study (03_xfem_study --only PARTS) and
# replaces only their files here: ladders (ladder.csv, reference.csv, section.csv), offsets
# (ladder_offsets.csv), sweep (front_sweep.csv), fraction (fraction.csv, fraction_uncut.csv).
# study_stdout.txt is replaced by the run's printed summary, or, for some parts only, kept as
# study_stdout_PARTS.txt beside it.
#
# The timings are one-core timings: we pin OpenBLAS (CHOLMOD's BLAS) and OpenMP (CalculiX) to a
# single thread. The benchmark behind the chapter's speed table is separate:
# cmake --build BUILD_DIR --target bench.
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
parts=${2:-ladders,offsets,sweep,fraction}
study="$build/bin/03_xfem_study"
if [ ! -x "$study" ]; then
  echo "make_figures.sh: $study not found; build it first: cmake --build $build --target 03_xfem_study" >&2
  exit 1
fi
command -v gnuplot > /dev/null || { echo "make_figures.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$study" --out "$out" --only "$parts" | tee "$out/study_stdout.txt"
has() { case ",$parts," in *",$1,"*) return 0 ;; *) return 1 ;; esac; }
copy() { for csv in "$@"; do cp "$out/$csv" "$here/$csv"; done; }
has ladders && copy ladder.csv reference.csv section.csv
has offsets && copy ladder_offsets.csv
has sweep && copy front_sweep.csv
has fraction && copy fraction.csv fraction_uncut.csv
if [ "$parts" = "ladders,offsets,sweep,fraction" ]; then
  cp "$out/study_stdout.txt" "$here/study_stdout.txt"
else
  cp "$out/study_stdout.txt" "$here/study_stdout_$(echo "$parts" | tr ',' '_').txt"
fi

cd "$here"
gnuplot ladder_dofs.gp
gnuplot ladder_time.gp
gnuplot fraction.gp
gnuplot section.gp
gnuplot front_sweep.gp
echo "wrote $(ls "$here"/*.png | tr '\n' ' ')"
