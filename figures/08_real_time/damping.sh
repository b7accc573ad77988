#!/bin/bash
# Chapter 8's demo (examples/08_liver_real_time.json: the wedge liver at 10k tets) under three
# members of Newmark's family, gamma = 0.5 (the average acceleration rule), 0.55 (the demo's) and
# 0.6, each with beta = (gamma + 1/2)^2 / 4, stepped by chapter 8 at 4 iterations a step and by
# chapter 7's Newton step solved to 1e-9 (CHOLMOD), frames off. Six probes in the front half
# write their displacement every step. Writes here
#   real_time_wedge.png   the wedge at rest from the demo's camera (its first frame)
#   damping.csv           one row a run: program, gamma, the step's mean ms, the steps the energy
#                         check sent on, gravity's work and the rest of the energy balance at 3 s
#                         (J), and for chapter 8's runs: the largest distance of a probe from
#                         chapter 7's at the same gamma over the largest displacement (e_history),
#                         the final sag (the largest downward displacement of a probe at 3 s) and
#                         the mean opening of the wound at 3 s, each against chapter 7's (e_sag,
#                         e_opening)
#   damping.md            the table
# The rest of the balance (energy.csv's "numerical") is what the step lost (> 0) or made (< 0).
#
#   figures/08_real_time/damping.sh [BUILD_DIR]     (default: build/release; about 4 minutes)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v xvfb-run > /dev/null || { echo "damping.sh: xvfb-run not found (apt-get install xvfb)" >&2; exit 1; }
cmake --build "$build" -j2 --target 07_liver 08_real_time
work=$root/output/figures_08_damping
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
demo=$root/examples/08_liver_real_time.json
printf "x,y,z\n-0.05,-0.04,0.0\n0.04,-0.04,0.0\n-0.09,-0.02,0.02\n0.0,-0.05,0.01\n-0.06,0.01,0.03\n-0.02,-0.02,0.02\n" > "$work/probes.csv"

# scene.py OUT STEPS RENDER_EVERY GAMMA [newton]: the demo's scene with that gamma.
cat > "$work/scene.py" << 'PY'
import json, sys
out, steps, every, gamma = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
scene = json.load(open(sys.argv[5]))
scene["time"].update({"steps": steps, "gamma": gamma, "beta": (gamma + 0.5) ** 2 / 4})
scene["output"] = {"every": 1000}
if len(sys.argv) > 6:
    del scene["time"]["iterations"]
    scene["solver"] = {"type": "cholmod"}
    scene["time"].update({"corotation": "newton", "tolerance": 1e-9})
if every == 0:
    scene["render"] = {"every": 0}
else:
    scene["render"]["every"] = every
json.dump(scene, open(out, "w"), indent=2)
PY

python3 "$work/scene.py" "$work/rest.json" 1 1 0.55 "$demo"
xvfb-run -a "$build/bin/08_real_time" --quiet --scene "$work/rest.json" --out "$work/rest" > /dev/null
cp "$work/rest/frames/liver_real_time_frame_000001.png" "$here/real_time_wedge.png"

for gamma in 0.5 0.55 0.6; do
  echo "damping.sh: gamma = $gamma"
  python3 "$work/scene.py" "$work/qn_$gamma.json" 300 0 $gamma "$demo"
  python3 "$work/scene.py" "$work/newton_$gamma.json" 300 0 $gamma "$demo" newton
  for run in "08_real_time qn_$gamma" "07_liver newton_$gamma"; do
    read -r program name <<< "$run"
    mkdir -p "$work/$name"
    "$build/bin/$program" --quiet --scene "$work/$name.json" --out "$work/$name" \
      --probes "$work/probes.csv" --probes-history "$work/$name/history.csv" > /dev/null
  done
done

python3 - "$work" "$here/damping.csv" "$here/damping.md" << 'PY'
import csv, math, sys
work, out_csv, out_md = sys.argv[1:]
def table(run, name): return list(csv.DictReader(open(f"{work}/{run}/{name}")))
def history(run):
    h = {}
    for r in table(run, "history.csv"):
        h[(r["step"], r["probe"])] = [float(r[k]) for k in ("ux", "uy", "uz")]
    return h
def sag(run):
    h = history(run)
    last = max(int(step) for step, _ in h)
    return max(-v[2] for (step, _), v in h.items() if int(step) == last and not any(math.isnan(x) for x in v))
def e_history(run, reference):
    a, b = history(run), history(reference)
    inside = [k for k, v in b.items() if not any(math.isnan(x) for x in v)]
    largest = max(math.dist(b[k], (0, 0, 0)) for k in inside)
    return max(math.dist(a[k], b[k]) for k in inside) / largest
rows = []
for gamma in ("0.5", "0.55", "0.6"):
    for program, run in (("08_real_time", "qn_" + gamma), ("07_liver", "newton_" + gamma)):
        timings, energy = table(run, "timings.csv"), table(run, "energy.csv")[-1]
        # Chapter 7's timings.csv has its parts in seconds: its simulate time is blade + topology + assemble + solve.
        ms = sum(float(r["simulate_ms"]) if "simulate_ms" in r else
                 1e3 * sum(float(r[k]) for k in ("blade_s", "topology_s", "assemble_s", "solve_s")) for r in timings) / len(timings)
        sent_on = sum(int(r["iterations"]) > 8 for r in timings) if program == "08_real_time" else ""
        row = {"program": program, "gamma": gamma, "ms_per_step": f"{ms:.2f}", "sent_on": sent_on,
               "work_J": f"{float(energy['external_work']):.4f}", "rest_J": f"{float(energy['numerical']):.5f}",
               "e_history": "", "e_sag": "", "e_opening": ""}
        if program == "08_real_time":
            reference = "newton_" + gamma
            opening = float(table(run, "opening.csv")[-1]["mean_opening"]) / float(table(reference, "opening.csv")[-1]["mean_opening"]) - 1
            row.update(e_history=f"{e_history(run, reference):.4f}", e_sag=f"{sag(run) / sag(reference) - 1:+.4f}",
                       e_opening=f"{opening:+.4f}")
        rows.append(row)
# Chapter 7's answer itself, against the average acceleration rule's: what the damping changes.
changes = {g: e_history("newton_" + g, "newton_0.5") for g in ("0.55", "0.6")}
with open(out_csv, "w", newline="") as f:
    writer = csv.DictWriter(f, fieldnames=list(rows[0]))
    writer.writeheader()
    writer.writerows(rows)
with open(out_md, "w") as md:
    md.write("| program | gamma | ms a step | steps sent on | work (J) | rest of the balance (J) | rest / work | trajectories against chapter 7 | "
             "final sag against chapter 7 | opening against chapter 7 |\n")
    md.write("|---|---|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        percent = lambda x: f"{100 * float(x):.2f} %" if x != "" else "-"
        md.write(f"| {r['program']} | {r['gamma']} | {r['ms_per_step']} | {r['sent_on'] if r['sent_on'] != '' else '-'} | {r['work_J']} | "
                 f"{r['rest_J']} | {100 * float(r['rest_J']) / float(r['work_J']):+.1f} % | {percent(r['e_history'])} | {percent(r['e_sag'])} | "
                 f"{percent(r['e_opening'])} |\n")
    md.write("\nChapter 7's Newton step at gamma = 0.55 and 0.6 against itself at 0.5 (the probes' largest distance over the largest "
             f"displacement): {100 * changes['0.55']:.2f} % and {100 * changes['0.6']:.2f} %.\n")
print(open(out_md).read())
PY
