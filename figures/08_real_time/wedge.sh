#!/bin/bash
# The wedge liver (mesh.liver.shape "wedge", mesh/liver_wedge.hpp) and why chapter 8's demo does
# not cut it yet. The demo's scene (examples/08_liver_real_time.json) with the wedge: the blade's
# path mirrored in x (the wedge's right lobe lies at -x, as an atlas shows it from the front), the
# left lobe's back held as well as the demo's two strips (it rests on the stomach), the camera in
# front. Runs build/release/bin/08_real_time and 07_liver and writes here
#   real_time_wedge.png       the wedge at rest (the first frame)
#   real_time_wedge_cut.png   the cut at t = 3 s, 10k tets, 5 iterations a step
#   wedge.csv                 one row a run: program, tets, iterations, the step's mean ms, the
#                             external work and the rest of the energy balance at t = 3 s (J)
#   wedge.md                  the table
# The rest of the balance (energy.csv's "numerical") is the energy the step lost (> 0) or made
# (< 0); chapter 7's Newton step, solved to 1e-9, is the reference.
#
#   figures/08_real_time/wedge.sh [BUILD_DIR]     (default: build/release; about 2 minutes)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v xvfb-run > /dev/null || { echo "wedge.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j2 --target 07_liver 08_real_time
work=$root/output/figures_08_wedge
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1

# scene.py OUT TETS ITERATIONS STEPS RENDER_EVERY [newton]: the demo's scene on the wedge.
cat > "$work/scene.py" << 'PY'
import json, sys
out, tets, iterations, steps, every = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]), int(sys.argv[5])
scene = json.load(open(sys.argv[6]))
scene["name"] = "liver_wedge"
scene["mesh"]["liver"] = {"tets": tets, "shape": "wedge"}
scene["dirichlet"].append({"region": {"box": {"min": [0.0, -1, -1], "max": [1, 1, -0.01]}}})
scene["blade"]["path"] = [{"time": 0.5, "edge": [[-0.12, -0.005, 0.09], [-0.12, -0.005, 0.0]]},
                          {"time": 1.3, "edge": [[0.0, 0.002, 0.09], [0.0, 0.002, 0.005]]},
                          {"time": 2.1, "edge": [[0.14, -0.012, 0.09], [0.14, -0.012, 0.012]]}]
scene["time"]["steps"] = steps
scene["output"] = {"every": 1000}
if len(sys.argv) > 7:
    del scene["time"]["iterations"]
    scene["solver"] = {"type": "cholmod"}
    scene["time"].update({"corotation": "newton", "tolerance": 1e-9})
else:
    scene["time"]["iterations"] = iterations
scene["render"] = {"every": every, "width": 960, "height": 720, "camera": {"azimuth": -110, "elevation": 25, "zoom": 1.3}} if every else {"every": 0}
json.dump(scene, open(out, "w"), indent=2)
PY
demo=$root/examples/08_liver_real_time.json

python3 "$work/scene.py" "$work/rest.json" 10000 4 1 1 "$demo"
xvfb-run -a "$build/bin/08_real_time" --quiet --scene "$work/rest.json" --out "$work/rest" > /dev/null
cp "$work/rest/frames/liver_wedge_frame_000001.png" "$here/real_time_wedge.png"
python3 "$work/scene.py" "$work/cut.json" 10000 5 300 300 "$demo"
xvfb-run -a "$build/bin/08_real_time" --quiet --scene "$work/cut.json" --out "$work/cut" > /dev/null
cp "$work/cut/frames/liver_wedge_frame_000300.png" "$here/real_time_wedge_cut.png"

echo "program,tets,iterations,ms_per_step,work_J,rest_J" > "$here/wedge.csv"
row() { # program tets iterations run_dir
  python3 - "$@" >> "$here/wedge.csv" << 'PY'
import csv, sys
program, tets, iterations, run = sys.argv[1:]
timings = list(csv.DictReader(open(run + "/timings.csv")))
energy = list(csv.DictReader(open(run + "/energy.csv")))[-1]
# Chapter 7's timings.csv has its parts in seconds: its simulate time is blade + topology + assemble + solve.
step_ms = (lambda r: float(r["simulate_ms"])) if "simulate_ms" in timings[0] else \
    (lambda r: 1e3 * sum(float(r[k]) for k in ("blade_s", "topology_s", "assemble_s", "solve_s")))
ms = sum(step_ms(r) for r in timings) / len(timings)
print(f"{program},{tets},{iterations},{ms:.2f},{float(energy['external_work']):.4f},{float(energy['numerical']):.5f}")
PY
}
for tets in 9000 10000 11000; do
  for iterations in 4 5 8; do
    echo "wedge.sh: 08_real_time, $tets tets, $iterations iterations"
    python3 "$work/scene.py" "$work/s.json" $tets $iterations 300 0 "$demo"
    "$build/bin/08_real_time" --quiet --scene "$work/s.json" --out "$work/r_${tets}_$iterations" > /dev/null
    row 08_real_time $tets $iterations "$work/r_${tets}_$iterations"
  done
done
echo "wedge.sh: 07_liver (Newton, 1e-9), 10000 tets"
python3 "$work/scene.py" "$work/n.json" 10000 0 300 0 "$demo" newton
"$build/bin/07_liver" --quiet --scene "$work/n.json" --out "$work/newton" > /dev/null
row 07_liver 10000 newton "$work/newton"

python3 - "$here/wedge.csv" "$here/wedge.md" << 'PY'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
with open(sys.argv[2], "w") as md:
    md.write("| program | tets | iterations a step | ms a step | work (J) | rest of the balance (J) | rest / work |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        md.write(f"| {r['program']} | {r['tets']} | {r['iterations']} | {r['ms_per_step']} | {r['work_J']} | {r['rest_J']} | "
                 f"{100 * float(r['rest_J']) / float(r['work_J']):+.1f} % |\n")
print(open(sys.argv[2]).read())
PY
