#!/bin/sh
# Draws frames of chapter 6's demo: runs the program's demo (the beam lying on its side under
# gravity, its top flap cut free but for a strip at x = 0.03) and draws four frames of the .pvd
# series it writes, the XFEM view moved by its displacement (warp 1), seen from y < 0 (x to the
# right, z up), coloured by piece (grey: tets drawn whole; blue and orange: the pieces of the
# split tets below and above the cut). Each picture fits its own body, so the scale differs a
# little from frame to frame.
#   frame_000.png  t = 0      at rest, undeformed
#   frame_040.png  t = 0.2 s  the first and largest swing
#   frame_080.png  t = 0.4 s  back near the start
#   frame_300.png  t = 1.5 s  settling
# Drawn off-screen through X, under xvfb-run (apt-get install xvfb; ./kerf.sh installs it).
#
#   figures/06_newmark/render_frames.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_frames.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 06_newmark render_pieces
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1 "$build/bin/06_newmark" --quiet --out "$out"
for step in 000 040 080 300; do
  xvfb-run -a "$build/bin/render_pieces" "$out/beam_flap_pieces_000$step.vtu" "$here/frame_$step.png" \
    --warp 1 --color piece --azimuth -90 --elevation 0 --zoom 1.1 --size 500x700
done
echo "wrote $(ls "$here"/frame_*.png | tr '\n' ' ')"
