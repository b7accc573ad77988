#!/bin/sh
# Draws the liver of our own: the 10k-tet mesh make_liver_mesh makes (07_liver_mesh_study, part
# "picture"), coloured by each tet's smallest dihedral angle, into two pictures here:
#   liver_mesh.png          the whole organ from the front (-y), from above: the large
#                           right lobe, the smaller left lobe, the saddle where they blend
#   liver_mesh_section.png  clipped by the plane y = 0 and seen straight on from y < 0 (x to the
#                           right, z up): the tets inside, and the flat underside
# The pictures are drawn off-screen through X, under xvfb-run (apt-get install xvfb; ./kerf.sh
# installs it).
#
#   figures/07_liver/render_liver.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_liver.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 07_liver_mesh_study render_pieces

out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
"$build/bin/07_liver_mesh_study" --only picture --out "$out"
mesh="$out/liver_mesh.vtu"
xvfb-run -a "$build/bin/render_pieces" "$mesh" "$here/liver_mesh.png" \
  --warp 0 --color min_dihedral_angle --azimuth -70 --elevation 35 --zoom 1.0 --size 900x700
xvfb-run -a "$build/bin/render_pieces" "$mesh" "$here/liver_mesh_section.png" \
  --warp 0 --color min_dihedral_angle --clip-plane 0,0,0,0,1,0 --azimuth -90 --elevation 0 --zoom 1.0 --size 900x600
