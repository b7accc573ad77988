#!/bin/bash
# Chapter 8's demo as the README and the results page show it: runs 08_real_time without
# arguments (the 10k-tet liver, a curved incision through both lobes, 300 steps of 10 ms, a frame
# every 4 steps) and keeps here
#   demo_stdout.txt            what it printed
#   demo_timings.csv           its time per step by part (timings.csv)
#   demo_cuts.csv              its changes of topology, with the volume, mass and energy checks
#   demo_rebuilds.csv          what each change spent its time on
#   real_time_frame.png        the last frame (t = 3 s), as the program drew it
#   real_time_frame_strip.png  four frames side by side: t = 0.52 s (the blade at the skin),
#                              1.32 s, 2.12 s (the blade has left the organ) and 3 s, cropped to
#                              the organ, shrunk twice
#   real_time_small.png        the run as an animated PNG, 480 x 360, a frame every 10 steps (a
#                              second run of the demo scene at that size: the README links it)
#   real_time_steps.png        each step's simulate time, by part, against t
# The program draws through X: without a screen it runs under xvfb-run (apt-get install xvfb).
#
#   figures/08_real_time/demo.sh [BUILD_DIR]     (default: build/release; about 2 minutes)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
for tool in gnuplot xvfb-run; do
  command -v $tool > /dev/null || { echo "demo.sh: $tool not found (apt-get install gnuplot-nox xvfb)" >&2; exit 1; }
done
cmake --build "$build" -j2 --target 08_real_time 07_frame_strip
work=$root/output/figures_08_demo
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
# The command of the results page, run in a scratch folder so that it prints the same paths.
(cd "$work" && xvfb-run -a "$build/bin/08_real_time" --out output/08_real_time) > "$here/demo_stdout.txt"
cat "$here/demo_stdout.txt"
run=$work/output/08_real_time
cp "$run/timings.csv" "$here/demo_timings.csv"
cp "$run/cuts.csv" "$here/demo_cuts.csv"
cp "$run/rebuilds.csv" "$here/demo_rebuilds.csv"
cp "$run/frames/liver_real_time_frame_000300.png" "$here/real_time_frame.png"
frames=""
for step in 000052 000132 000212 000300; do frames="$frames $run/frames/liver_real_time_frame_$step.png"; done
# shellcheck disable=SC2086 # the frames are one word each
"$build/bin/07_frame_strip" "$here/real_time_frame_strip.png" $frames --shrink 2
python3 - "$root/examples/08_liver_real_time.json" "$work/small.json" << 'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "liver_small"
scene["render"].update({"every": 10, "width": 480, "height": 360})
scene["output"] = {"every": 100000}
json.dump(scene, open(sys.argv[2], "w"), indent=2)
EOF
xvfb-run -a "$build/bin/08_real_time" --quiet --scene "$work/small.json" --out "$work/small"
cp "$work/small/liver_small.png" "$here/real_time_small.png"

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 1000,420 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "real_time_steps.png"
set datafile separator ","
set grid lc rgb "#dddddd"
set key top left opaque box font ",9"
set xlabel "t (s)"
set ylabel "ms"
set title "08\\_real\\_time's demo, 10k tets: each step's time by part (demo\\_timings.csv); dt = 10 ms"
set style fill solid 0.8 noborder
plot "demo_timings.csv" using "t":(column("local_ms") + column("global_ms") + column("other_ms") + column("blade_ms") + column("topology_ms")) \
       w boxes lc rgb "#ff7f0e" t "topology (a change of the cut)", \
     "" using "t":(column("local_ms") + column("global_ms") + column("other_ms") + column("blade_ms")) w boxes lc rgb "#7f7f7f" t "blade and other", \
     "" using "t":(column("local_ms") + column("global_ms")) w boxes lc rgb "#2ca02c" t "global (solves)", \
     "" using "t":"local_ms" w boxes lc rgb "#1f77b4" t "local (pieces)", \
     10 w l dt 2 lc rgb "#000000" t "dt"
EOF
echo "wrote $here/demo_*.csv, demo_stdout.txt, real_time_frame.png, real_time_frame_strip.png, real_time_small.png, real_time_steps.png"
