#!/bin/bash
# Chapter 7's sinusoidal cut (Paulus et al. section 5.3, their Fig. 10): a blade whose edge swings
# as a sine (amplitude 12 mm, wavelength 80 mm) while it crosses part of the 10k-tet liver, down to
# z = 0 only, so that the cut's front stays inside the organ; the wound's opening against time,
# beside the demo's straight cut through the same part of the organ. Runs
# examples/07_liver_sine_cut.json and examples/07_liver_cut.json (frames off) with
# build/release/bin/07_liver, reads their opening.csv (xfem/cut_opening.hpp: the jump of the field
# across the cut, integrated over the cut) and writes here
#   sine_cut.csv         t, and per cut: its area in the organ, the gap's volume, the mean and the
#                        largest normal opening,
#   sine_cut.png         the mean and the largest opening against time, both cuts,
#   sine_cut_frames.png  the sine run's frames at t = 1.0, 1.5 and 2.5 s, side by side,
#   sine_cut.md          the numbers at the end of the blade's path and of the run.
#
#   figures/07_liver/sine_cut.sh [BUILD_DIR]     (default: build/release; about 2 minutes)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
for tool in gnuplot xvfb-run; do
  command -v $tool > /dev/null || { echo "sine_cut.sh: $tool not found (apt-get install gnuplot-nox xvfb)" >&2; exit 1; }
done
cmake --build "$build" -j2 --target 07_liver 07_frame_strip
work=$root/output/figures_07_sine_cut
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
python3 - "$root/examples/07_liver_cut.json" "$work/straight.json" << 'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "liver_straight_cut"
scene["render"] = {"every": 0}
scene["output"] = {"every": 250}
json.dump(scene, open(sys.argv[2], "w"), indent=2)
EOF
xvfb-run -a "$build/bin/07_liver" --scene "$root/examples/07_liver_sine_cut.json" --out "$work/sine" | tee "$work/sine_stdout.txt"
"$build/bin/07_liver" --scene "$work/straight.json" --out "$work/straight" > "$work/straight_stdout.txt"
frames=""
for step in 000100 000150 000250; do frames="$frames $work/sine/frames/liver_sine_cut_frame_$step.png"; done
# shellcheck disable=SC2086 # the frames are one word each
"$build/bin/07_frame_strip" "$here/sine_cut_frames.png" $frames --shrink 2
cp "$work/sine_stdout.txt" "$here/sine_cut_stdout.txt"

python3 - "$work/sine/opening.csv" "$work/straight/opening.csv" "$here/sine_cut.csv" "$here/sine_cut.md" << 'EOF'
import csv, sys
sine = list(csv.DictReader(open(sys.argv[1])))
straight = list(csv.DictReader(open(sys.argv[2])))
assert len(sine) == len(straight)
with open(sys.argv[3], "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["t", "sine_area", "sine_gap", "sine_mean_mm", "sine_max_mm", "straight_area", "straight_gap", "straight_mean_mm", "straight_max_mm"])
    for a, b in zip(sine, straight):
        w.writerow([a["t"]] + [f"{float(r[k]) * s:.6g}" for r in (a, b) for k, s in
                               (("cut_area", 1), ("gap_volume", 1), ("mean_opening", 1e3), ("max_opening", 1e3))])
def at(rows, t):
    return min(rows, key=lambda r: abs(float(r["t"]) - t))
def peak(rows, key):
    return max(rows, key=lambda r: float(r[key]))
out = []
p = out.append
p("# Chapter 7: the sinusoidal cut, opening against time")
p("")
p("![the mean and the largest opening of the sine cut and of the straight cut against time](sine_cut.png)")
p("")
p("![the sine cut at t = 1.0, 1.5 and 2.5 s](sine_cut_frames.png)")
p("")
p("Made by `figures/07_liver/sine_cut.sh` (runs examples/07_liver_sine_cut.json and the demo scene")
p("examples/07_liver_cut.json without frames; `sine_cut.csv`). The blade enters at t = 0.5 s and stops")
p("inside the organ at 1.7 s; the run ends at 2.5 s. Opening: the jump [[u]] . n of the displacement across")
p("the cut, sampled every half mean edge (xfem/cut_opening.hpp); the mean is the gap's volume over the cut's")
p("area in the organ.")
p("")
p("| cut | t (s) | cut area (cm^2) | gap volume (cm^3) | mean opening (mm) | largest opening (mm) |")
p("|---|---|---|---|---|---|")
for name, rows in (("sine", sine), ("straight", straight)):
    for label, r in (("1.7 (blade stops)", at(rows, 1.7)), ("2.5 (end)", at(rows, 2.5)),
                     (f"{float(peak(rows, 'mean_opening')['t']):.2f} (largest mean)", peak(rows, "mean_opening"))):
        p(f"| {name} | {label} | {float(r['cut_area']) * 1e4:.1f} | {float(r['gap_volume']) * 1e6:.3f} | "
          f"{float(r['mean_opening']) * 1e3:.2f} | {float(r['max_opening']) * 1e3:.2f} |")
open(sys.argv[4], "w").write("\n".join(out) + "\n")
print("\n".join(out))
EOF

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 1100,520 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "sine_cut.png"
set datafile separator ","
set key top left opaque box font ",10"
set grid lc rgb "#dddddd"
set xlabel "t (s)"
set ylabel "opening [[u]] . n (mm)"
set title "07\\_liver: the wound's opening under gravity (sine\\_cut.csv; the blade cuts from 0.5 s to 1.7 s)"
set object 1 rect from 0.5, graph 0 to 1.7, graph 1 fc rgb "#f2f2f2" fs solid noborder behind
plot "sine_cut.csv" using 1:(column("sine_mean_mm")) w l lw 2 lc rgb "#1f77b4" t "sine cut: mean", \
     "" using 1:(column("sine_max_mm")) w l lw 2 dt 2 lc rgb "#1f77b4" t "sine cut: largest", \
     "" using 1:(column("straight_mean_mm")) w l lw 2 lc rgb "#d62728" t "straight cut: mean", \
     "" using 1:(column("straight_max_mm")) w l lw 2 dt 2 lc rgb "#d62728" t "straight cut: largest"
EOF
echo "sine_cut.sh: wrote $here/sine_cut.{csv,png,md} and sine_cut_frames.png"
