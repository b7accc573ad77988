#!/bin/bash
# Chapter 8's speed against accuracy: chapter 7's example scene (examples/07_liver_cut.json, the
# demo's straight cut, frames off) at 2k and 10k tets, run by
#   - chapter 7's Newton step (CHOLMOD) to a relative residual of 1e-9: the reference;
#   - chapter 7's default, the checked step (CG, 1e-3);
#   - chapter 8's step at 2, 3, 4, 6 and 10 quasi-Newton iterations a step, and solved to 1e-9.
# Each run writes the displacement at six probes in the front half every step; the error of a run
# is the largest distance of its probes from the reference's over all 250 steps, over the
# reference's largest displacement. Also the final sag (the largest downward displacement of a
# probe at 2.5 s) and the wound's mean opening at 2.5 s (opening.csv), each against the
# reference's. The cost is the mean simulate time of a step (timings.csv: blade, topology and
# the step; no output), one core. Writes here
#   accuracy.csv   one row a run: tets, program, iterations, ms_per_step, e_history, e_sag, e_opening
#   real_time_accuracy.png   e_history against ms a step, one line a mesh size, chapter 7's two steps beside
#   accuracy.md    the table
#
#   figures/08_real_time/accuracy.sh [BUILD_DIR]     (default: build/release; about 4 minutes)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v gnuplot > /dev/null || { echo "accuracy.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
cmake --build "$build" -j2 --target 07_liver 08_real_time
work=$root/output/figures_08_accuracy
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
printf "x,y,z\n0.05,-0.04,0.0\n-0.04,-0.04,0.0\n0.09,-0.02,0.02\n0.0,-0.05,0.01\n0.06,0.01,0.03\n0.02,-0.02,0.02\n" > "$work/probes.csv"

# name, program, tets, what the scene's "time" and "solver" get.
runs=()
for tets in 2000 10000; do
  runs+=("newton_$tets 07_liver $tets newton" "checked_$tets 07_liver $tets checked")
  for iterations in 2 3 4 6 10 0; do runs+=("qn${iterations}_$tets 08_real_time $tets $iterations"); done
done
for run in "${runs[@]}"; do
  read -r name program tets setting <<< "$run"
  python3 - "$root/examples/07_liver_cut.json" "$work/$name.json" "$tets" "$setting" << 'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["mesh"]["liver"]["tets"] = int(sys.argv[3])
scene["render"] = {"every": 0}
scene["output"] = {"every": 250}
setting = sys.argv[4]
if setting == "newton":
    scene["time"].update({"corotation": "newton", "tolerance": 1e-9})
    scene["solver"] = {"type": "cholmod"}
elif setting != "checked":
    scene["time"]["iterations"] = int(setting)
    if int(setting) == 0:
        scene["time"]["tolerance"] = 1e-9
json.dump(scene, open(sys.argv[2], "w"), indent=2)
EOF
  echo "accuracy.sh: $name"
  mkdir -p "$work/$name"
  # A run that diverges (2 iterations a step at 10k tets does) stops with one line; it is kept as such.
  "$build/bin/$program" --quiet --scene "$work/$name.json" --out "$work/$name" \
    --probes "$work/probes.csv" --probes-history "$work/$name/history.csv" 2> "$work/$name/stderr.txt" ||
    { cat "$work/$name/stderr.txt"; touch "$work/$name/diverged"; }
done

python3 - "$work" "$here/accuracy.csv" "$here/accuracy.md" << 'EOF'
import csv, math, os, sys
work, out_csv, out_md = sys.argv[1:]

def history(name):
    rows = list(csv.DictReader(open(f"{work}/{name}/history.csv")))
    return {(int(r["step"]), int(r["probe"])): (float(r["ux"]), float(r["uy"]), float(r["uz"])) for r in rows}

def ms_per_step(name, program):
    rows = list(csv.DictReader(open(f"{work}/{name}/timings.csv")))
    rows = [r for r in rows if int(r["step"]) > 0]
    if program == "08_real_time":
        return sum(float(r["simulate_ms"]) for r in rows) / len(rows)
    return 1e3 * sum(float(r["blade_s"]) + float(r["topology_s"]) + float(r["assemble_s"]) + float(r["solve_s"]) for r in rows) / len(rows)

def opening(name):
    return float(list(csv.DictReader(open(f"{work}/{name}/opening.csv")))[-1]["mean_opening"])

rows = []
for tets in (2000, 10000):
    ref = history(f"newton_{tets}")
    last = max(k[0] for k in ref)
    probes = max(k[1] for k in ref) + 1
    largest = max(math.dist(v, (0, 0, 0)) for v in ref.values())
    sag = lambda h: max(-h[(last, p)][2] for p in range(probes))
    names = [("newton", "07_liver", "Newton"), ("checked", "07_liver", "checked")] + \
            [(f"qn{i}", "08_real_time", str(i) if i else "tight") for i in (2, 3, 4, 6, 10, 0)]
    for prefix, program, iterations in names:
        name = f"{prefix}_{tets}"
        if os.path.exists(f"{work}/{name}/diverged"):
            rows.append({"tets": tets, "program": program, "iterations": iterations, "ms_per_step": round(ms_per_step(name, program), 3),
                         "e_history": "diverged", "e_sag": "diverged", "e_opening": "diverged"})
            continue
        h = history(name)
        e = max(math.dist(h[k], ref[k]) for k in ref) / largest
        rows.append({"tets": tets, "program": program, "iterations": iterations, "ms_per_step": round(ms_per_step(name, program), 3),
                     "e_history": f"{e:.3e}", "e_sag": f"{abs(sag(h) / sag(ref) - 1):.3e}",
                     "e_opening": f"{abs(opening(name) / opening(f'newton_{tets}') - 1):.3e}"})
with open(out_csv, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
with open(out_md, "w") as f:
    f.write("# Chapter 8: accuracy against cost on chapter 7's scene\n\n![error against ms a step](real_time_accuracy.png)\n\n"
            "Made by\n\n    figures/08_real_time/accuracy.sh     # about 4 minutes\n\n"
            "Errors against chapter 7's Newton step solved to 1e-9 (e_history: the largest probe distance over all steps over the "
            "largest displacement; e_sag, e_opening: relative, at 2.5 s). One core; ms a step: blade, topology and step.\n\n"
            "| tets | program | iterations | ms a step | e_history | e_sag | e_opening |\n|---|---|---|---|---|---|---|\n")
    for r in rows:
        pct = lambda x: x if x == "diverged" else f"{float(x):.2%}"
        f.write(f"| {r['tets']} | {r['program']} | {r['iterations']} | {r['ms_per_step']} | {pct(r['e_history'])} | "
                f"{pct(r['e_sag'])} | {pct(r['e_opening'])} |\n")
EOF
cat "$here/accuracy.md"

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 900,600 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "real_time_accuracy.png"
set datafile separator ","
set logscale xy
set grid lc rgb "#dddddd"
set xlabel "ms a step (one core: blade, topology, step)"
set ylabel "largest probe error over the run / largest displacement"
set title "08\\_real\\_time against chapter 7's Newton step on chapter 7's scene (accuracy.csv)"
set key top right opaque box font ",10"
set arrow from graph 0, first 0.02 to graph 1, first 0.02 nohead dt 2 lc rgb "#888888"
set label "2 %" at graph 0.02, first 0.024 font ",9" tc rgb "#666666"
qn(t) = (strcol("program") eq "08_real_time" && column("tets") == t && strcol("iterations") ne "tight") ? column("e_history") : 1/0
ch7(t) = (strcol("program") eq "07_liver" && column("tets") == t && strcol("iterations") eq "checked") ? column("e_history") : 1/0
plot "accuracy.csv" using "ms_per_step":(qn(2000)) w lp pt 7 ps 1.3 lc rgb "#1f77b4" t "chapter 8, 2k tets (2, 3, 4, 6, 10 iterations)", \
     "" using "ms_per_step":(qn(2000)):(strcol("iterations")) w labels left offset 0.7,0.5 font ",9" notitle, \
     "" using "ms_per_step":(qn(10000)) w lp pt 7 ps 1.3 lc rgb "#d62728" t "chapter 8, 10k tets", \
     "" using "ms_per_step":(qn(10000)):(strcol("iterations")) w labels left offset 0.7,0.5 font ",9" notitle, \
     "" using "ms_per_step":(ch7(2000)) w p pt 5 ps 1.5 lc rgb "#1f77b4" t "chapter 7, checked step, 2k", \
     "" using "ms_per_step":(ch7(10000)) w p pt 5 ps 1.5 lc rgb "#d62728" t "chapter 7, checked step, 10k"
EOF
echo "wrote $here/accuracy.csv, accuracy.md, real_time_accuracy.png"
