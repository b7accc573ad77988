#!/bin/sh
# Draws chapter 5's open cut: runs the chapter's demo (the beam cut half-way by the rectangle
# whose front x = 0.015, z = 0.1 lies inside elements, its top edge x = 0 pulled up by 0.02 m)
# and the same scene with "crack_tip": {"enrichment": "none"} (chapter 4's rule), and draws the
# XFEM views they write (NAME_pieces.vtu), moved by their displacement (warp factor 1), side by
# side and clipped by the plane y = 0.03, seen straight on from y < 0 (x to the right, z up),
# coloured by piece:
#   crack_tip_section.png  left: chapter 4's rule, the cut stops at x = 0.01; right: the demo with
#                         branch functions, the gap closes at the front x = 0.015
# The pictures are drawn off-screen through X, under xvfb-run (apt-get install xvfb; ./kerf.sh
# installs it).
#
#   figures/05_crack_tip/render_open_cut.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_open_cut.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 05_crack_tip render_pieces

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
cat > "$out/none.json" <<SCENE
{"name": "none", "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
 "material": {"young": 300e3, "poisson": 0.35, "density": 1070}, "model": "linear",
 "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
               {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
 "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
 "crack_tip": {"enrichment": "none"}}
SCENE
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/05_crack_tip" --quiet --scene "$out/none.json" --out "$out"
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/05_crack_tip" --quiet --out "$out"
xvfb-run -a "$build/bin/render_pieces" "$out/none_pieces.vtu" "$out/beam_crack_tip_pieces.vtu" "$here/crack_tip_section.png" \
  --warp 1 --color piece --clip-plane 0,0.03,0,0,1,0 --azimuth -90 --elevation 0 --zoom 3.5 --size 1200x800 --spacing 0.045
