#!/bin/sh
# The opening of chapter 5's demo cut under each crack-tip rule: runs 05_crack_tip on the demo's
# scene with "crack_tip" none, radius 0 (topological), radius 0.01 and the default, probes
# 0.5 mm above and below the cut at y = 0.03, and writes demo_openings.csv (the opening
# u_z above - u_z below at x = 0, 0.0075 and 0.025, the unknowns, the branch nodes) and
# demo_stdout.txt (the demo's own output) into this folder.
# Usage: figures/05_crack_tip/demo_openings.sh BUILD_DIR   (from the source tree)
set -eu
build=$1
here=$(dirname "$0")
work=$(mktemp -d)
program="$build/bin/05_crack_tip"
printf 'x,y,z\n0,0.03,0.1005\n0,0.03,0.0995\n0.0075,0.03,0.1005\n0.0075,0.03,0.0995\n0.025,0.03,0.1005\n0.025,0.03,0.0995\n' > "$work/probes.csv"
echo "crack_tip,unknowns,branch_nodes,opening_x0,opening_x0075,opening_x025" > "$here/demo_openings.csv"
for label in none topological radius_0.01 default; do
  case $label in
    none) rule='{"enrichment": "none"}' ;;
    topological) rule='{"radius": 0}' ;;
    radius_0.01) rule='{"radius": 0.01}' ;;
    default) rule='{"enrichment": "branch"}' ;;
  esac
  cat > "$work/scene.json" <<SCENE
{"name": "beam_crack_tip", "mesh": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0.2], "cells": [3, 6, 19]}, "order": 1},
 "material": {"young": 300e3, "poisson": 0.35, "density": 1070}, "model": "linear",
 "dirichlet": [{"region": {"box": {"min": [0, 0, 0], "max": [0.03, 0.06, 0]}}},
               {"region": {"box": {"min": [0, 0, 0.2], "max": [0, 0.06, 0.2]}}, "displacement": [0, 0, 0.02]}],
 "cuts": [{"rectangle": {"origin": [0, 0, 0.1], "edge1": [0.015, 0, 0], "edge2": [0, 0.06, 0]}}],
 "crack_tip": $rule}
SCENE
  "$program" --scene "$work/scene.json" --out "$work/out" --probes "$work/probes.csv" --probes-out "$work/u.csv" > "$work/stdout.txt"
  unknowns=$(sed -n 's/^system: \([0-9]*\) unknowns.*/\1/p' "$work/stdout.txt")
  branch=$(sed -n 's/.* \([0-9]*\) branch nodes.*/\1/p' "$work/stdout.txt")
  awk -F, -v rule="$label" -v n="$unknowns" -v b="$branch" \
    'NR > 1 { z[NR] = $6 } END { printf "%s,%s,%s,%.6g,%.6g,%.6g\n", rule, n, b, z[2] - z[3], z[4] - z[5], z[6] - z[7] }' \
    "$work/u.csv" >> "$here/demo_openings.csv"
done
program=$(cd "$(dirname "$program")" && pwd)/05_crack_tip
(cd "$work" && "$program" --out demo) > "$here/demo_stdout.txt"
rm -rf "$work"
cat "$here/demo_openings.csv"
