#!/bin/sh
# Runs chapter 7's demo (07_liver without arguments: the 10k-tet liver sagging under gravity
# while a blade crosses its right lobe, 250 steps of 10 ms) and lays five of its PNG frames side
# by side into liver_frame_strip.png here (07_frame_strip: each frame cropped to the organ, the same
# box for all, shrunk twice): t = 0 (at rest), 0.5 s (sagged, the blade at the skin), 1.0 s
# (half-way), 1.7 s (the blade stops inside) and 2.5 s (the end). It keeps what the demo printed
# (demo_stdout.txt), its changes of topology (demo_cuts.csv) and its time per step by stage
# (demo_timings.csv) beside the picture. The demo draws through X: without a screen it runs
# under xvfb-run (apt-get install xvfb).
#
#   figures/07_liver/frame_strip.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v xvfb-run > /dev/null || { echo "frame_strip.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 07_liver 07_frame_strip
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
# The command of the results page, run in a scratch folder so that it prints the same paths.
(cd "$out" && OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 xvfb-run -a "$build/bin/07_liver" --out output/07_liver) \
  > "$here/demo_stdout.txt"
cat "$here/demo_stdout.txt"
run=$out/output/07_liver
cp "$run/cuts.csv" "$here/demo_cuts.csv"
cp "$run/timings.csv" "$here/demo_timings.csv"
frames=""
for step in 000000 000050 000100 000170 000250; do
  frames="$frames $run/frames/liver_cut_frame_$step.png"
done
# shellcheck disable=SC2086 # the frames are one word each
"$build/bin/07_frame_strip" "$here/liver_frame_strip.png" $frames --shrink 2
