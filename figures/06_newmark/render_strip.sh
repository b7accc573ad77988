#!/bin/sh
# Draws chapter 6's demo as a frame strip: runs the program's demo (the beam lying on its side
# under gravity, its top flap cut free but for a strip at x = 0.03) and draws eight frames of
# the .pvd series it writes, t = 0, 0.05, ..., 0.35 s (every 10th step of 5 ms: the first
# swing out and back), side by side in one picture under one camera, so that they share one
# scale (render_pieces with several inputs; frame k drawn moved by k x 0.12 m along x). The
# XFEM view is moved by its displacement (warp 1), seen from y < 0 (x to the right, z up),
# coloured by piece (grey: tets drawn whole; blue and orange: the pieces of the split tets
# below and above the cut). Drawn off-screen through X, under xvfb-run (apt-get install xvfb).
#
#   figures/06_newmark/render_strip.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_strip.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_newmark render_pieces
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 "$build/bin/06_newmark" --quiet --out "$out"
frames=""
for step in 000 010 020 030 040 050 060 070; do
  frames="$frames $out/beam_flap_pieces_000$step.vtu"
done
# shellcheck disable=SC2086 # the frames are one word each
xvfb-run -a "$build/bin/render_pieces" $frames "$here/frame_strip.png" \
  --warp 1 --color piece --azimuth -90 --elevation 0 --spacing 0.12 --zoom 3.0 --size 2000x460
