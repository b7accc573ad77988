#!/bin/sh
# Draws chapter 4's open cut: runs the chapter's demo (the beam cut by the curved blade, its top
# edge x = 0 pulled up by 0.02 m) and draws the XFEM view it writes, beam_curved_cut_pieces.vtu,
# moved by its displacement (warp factor 1: the gap as wide as it opened), into two pictures here:
#   open_cut.png          the middle of the beam from the side of its faces x = 0 and y = 0, where
#                         the blade enters, a little from above; coloured by piece (grey: tets
#                         drawn whole, blue and orange: the pieces above and below the blade)
#   open_cut_section.png  the beam clipped by the plane y = 0.03, half-way across, seen straight
#                         on from y < 0 (x to the right, z up): the gap's wedge in section,
#                         coloured by piece as well
# The pictures are drawn off-screen through X, under xvfb-run (apt-get install xvfb; ./kerf.sh
# installs it).
#
#   figures/04_cut_quadrature/render_open_cut.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_open_cut.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 04_cut_quadrature render_pieces

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 "$build/bin/04_cut_quadrature" --quiet --out "$out"
pieces="$out/beam_curved_cut_pieces.vtu"
xvfb-run -a "$build/bin/render_pieces" "$pieces" "$here/open_cut.png" \
  --warp 1 --color piece --azimuth -125 --elevation 20 --zoom 2 --size 900x900
xvfb-run -a "$build/bin/render_pieces" "$pieces" "$here/open_cut_section.png" \
  --warp 1 --color piece --clip-plane 0,0.03,0,0,1,0 --azimuth -90 --elevation 0 --zoom 3 --size 900x900
