#!/bin/bash
# Chapter 8's window at the demo's size, driven as a hand would: five runs of
# `08_real_time --interactive` (the demo's scene: the wedge liver at 10k tets, a 960 x 720
# window) under xvfb-run, each with the same script keyed by wall time: Shift + the left button
# pressed left of the organ's middle at 0.5 s, dragged 320 pixels across it in 2 s, released at
# 2.6 s, q at 3 s. The cut differs from run to run (the events are keyed by wall time, the steps
# are not). Writes here
#   window.csv   one row a run: the real-time factor and the frames drawn (the program's summary),
#                the tets cut, the steps the energy check sent on (more than 8 evaluations), the
#                slowest step (ms), and whether the program warned that it fell behind
#   window.md    the table
#
#   figures/08_real_time/window.sh [BUILD_DIR]     (default: build/release; about a minute)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v xvfb-run > /dev/null || { echo "window.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j2 --target 08_real_time
work=$root/output/figures_08_window
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
{
  echo "time,event,x,y,shift"
  echo "0.5,press,330,360,1"
  awk 'BEGIN { for (k = 1; k <= 20; ++k) printf "%.1f,move,%d,360,1\n", 0.5 + 0.1 * k, 330 + 16 * k }'
  echo "2.6,release,650,360,1"
  echo "3.0,key_q,0,0,0"
} > "$work/drag.csv"
echo "run,factor,frames,tets_cut,sent_on,slowest_ms,fell_behind" > "$here/window.csv"
for run in 1 2 3 4 5; do
  echo "window.sh: run $run"
  xvfb-run -a "$build/bin/08_real_time" --interactive --events "$work/drag.csv" --out "$work/run_$run" > "$work/run_$run.txt" 2>&1
  python3 - "$work/run_$run" "$run" >> "$here/window.csv" << 'PY'
import csv, re, sys
out, run = sys.argv[1], sys.argv[2]
text = open(out + ".txt").read()
m = re.search(r"factor ([0-9.]+)\); ([0-9]+) frames drawn .*?; ([0-9]+) tets cut", text)
timings = list(csv.DictReader(open(out + "/timings.csv")))
sent_on = sum(int(r["iterations"]) > 8 for r in timings)
slowest = max(float(r["simulate_ms"]) for r in timings)
print(f"{run},{m.group(1)},{m.group(2)},{m.group(3)},{sent_on},{slowest:.1f},{int('behind real time' in text)}")
PY
done
python3 - "$here/window.csv" "$here/window.md" << 'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w") as md:
    md.write("| run | real-time factor | frames drawn | tets cut | steps sent on | slowest step (ms) | warned behind |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        md.write(f"| {r['run']} | {r['factor']} | {r['frames']} | {r['tets_cut']} | {r['sent_on']} | {r['slowest_ms']} | {'yes' if r['fell_behind'] == '1' else 'no'} |\n")
print(open(sys.argv[2]).read())
PY
