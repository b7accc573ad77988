#!/bin/sh
# Draws the liver's visual surface (3 mm triangles, smooth shading with vertex normals) beside the
# boundary of its 10k-tet mesh (faceted), into visual_surface.png here, the same surface on the
# liver cut through by a plane and opened 30 mm (visual_surface_cut.png), and writes the sizes,
# distances and seconds of the visual surfaces into visual_surface.csv and
# visual_surface_stdout.txt (07_visual_surface_study; figures/07_liver/visual_surface.md).
# The picture is drawn off-screen through X, under xvfb-run (apt-get install xvfb; ./kerf.sh
# installs it).
#
#   figures/07_liver/render_visual_surface.sh [BUILD_DIR]     (default: build/release)
set -eu
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=${1:-$root/build/release}
command -v xvfb-run > /dev/null || { echo "render_visual_surface.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j1 --target 07_visual_surface_study
xvfb-run -a "$build/bin/07_visual_surface_study" --out "$here" | tee "$here/visual_surface_stdout.txt"
