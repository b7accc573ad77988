#!/bin/bash
# Chapter 7's accuracy against cost: the demo's cut (examples/07_liver_cut.json, frames off) with
# Tet4 and Tet10, coarse and fine livers, lumped and consistent mass, each against the finest run
# (Tet10, consistent mass, the largest liver here). Every run writes the displacement at the same
# probe points at every step (--probes-history) and the wound's opening (opening.csv); the script
# writes here
#   accuracy.csv   per run: element, tets, mass, ms per step, and its errors against the finest:
#                  e_history, the RMS over the probes and the steps of |u - u_ref|, over the RMS of
#                  |u_ref|; e_end, the same at the last step; e_gap, |V_gap - V_gap_ref| / V_gap_ref
#                  at the last step,
#   accuracy.png   e_history and e_gap against ms per step: the "model no more than the scene
#                  needs" chart,
#   accuracy.md    the table and how it was measured.
#
#   figures/07_liver/accuracy.sh [BUILD_DIR]      (default: build/release; about 40 minutes)
#   figures/07_liver/accuracy.sh --charts         (only redraw accuracy.png and accuracy.md)
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
command -v gnuplot > /dev/null || { echo "accuracy.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
# Every run takes chapter 6's frozen step ("corotation": "frozen"), the step the study was made
# with; chapter 7's default, the checked step, costs about 2.3 times as much a step (chapter 7's
# results, "Where the time of a step goes") and the comparisons between runs are the same kind.
# name, element order, liver tets, mass, linear solver. The last is the reference. Tet4 runs
# keep 07_liver's default solver, conjugate gradients with a Jacobi preconditioner, which suits
# its well-conditioned M / (beta dt^2) + K; with Tet10 and the consistent mass that matrix is
# far worse conditioned, and at 20k tets one Newton step's CG did not converge in 5 minutes: the
# Tet10 runs use CHOLMOD's sparse Cholesky.
runs=(
  "tet4_2k_lumped 1 2000 lumped default" "tet4_2k_consistent 1 2000 consistent default"
  "tet4_10k_lumped 1 10000 lumped default" "tet4_10k_consistent 1 10000 consistent default"
  "tet4_40k_lumped 1 40000 lumped default"
  "tet10_2k_lumped 2 2000 lumped cholmod" "tet10_2k_consistent 2 2000 consistent cholmod"
  "tet10_10k_lumped 2 10000 lumped cholmod"
  "tet10_20k_consistent 2 20000 consistent cholmod"
)
if [ "${1:-}" != "--charts" ]; then
  build=$(cd "${1:-$root/build/release}" && pwd)
  cmake --build "$build" -j2 --target 07_liver
  # A run already made with the same scene and size (its scene file unchanged, all its steps in
  # timings.csv) is kept: KERF_ACCURACY_FRESH=1 runs everything again.
  work=$root/output/figures_07_accuracy
  [ "${KERF_ACCURACY_FRESH:-0}" = 1 ] && rm -rf "$work"
  mkdir -p "$work"
  export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
  # Probes: a 9 x 7 x 5 grid over the liver's box; those outside some run's mesh are dropped
  # below (07_liver writes nan for them).
  python3 - "$work/probes.csv" << 'EOF'
import sys
with open(sys.argv[1], "w") as f:
    f.write("x,y,z\n")
    for i in range(9):
        for j in range(7):
            for k in range(5):
                f.write(f"{-0.1 + 0.025 * i:.4f},{-0.075 + 0.025 * j:.4f},{-0.04 + 0.02 * k:.4f}\n")
EOF
  for run in "${runs[@]}"; do
    read -r name order tets mass solver <<< "$run"
    python3 - "$root/examples/07_liver_cut.json" "$work/$name.next.json" "$order" "$mass" "$solver" << 'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "liver_accuracy"
scene["mesh"]["order"] = int(sys.argv[3])
scene["time"]["mass"] = sys.argv[4]
if sys.argv[5] != "default":
    scene["solver"] = {"type": sys.argv[5]}
scene["render"] = {"every": 0}
scene["output"] = {"every": 250}
scene["time"]["corotation"] = "frozen"
json.dump(scene, open(sys.argv[2], "w"), indent=2)
EOF
    if cmp -s "$work/$name.next.json" "$work/$name.json" && [ -f "$work/$name/timings.csv" ] &&
       [ "$(wc -l < "$work/$name/timings.csv")" -eq 252 ] && grep -q "^$tets " "$work/$name.tets" 2> /dev/null; then
      echo "accuracy.sh: $name: kept from an earlier run" >&2
      rm "$work/$name.next.json"
      continue
    fi
    mv "$work/$name.next.json" "$work/$name.json"
    echo "$tets " > "$work/$name.tets"
    echo "accuracy.sh: $name" >&2
    "$build/bin/07_liver" --scene "$work/$name.json" --tets "$tets" --probes "$work/probes.csv" \
      --probes-history "$work/$name.history.csv" --out "$work/$name" > "$work/$name.stdout.txt" 2> "$work/$name.stderr.txt"
  done
  python3 - "$work" "$here/accuracy.csv" "${runs[@]}" << 'EOF'
import csv, math, re, sys
work, out, runs = sys.argv[1], sys.argv[2], [r.split() for r in sys.argv[3:]]
def history(name):
    rows = list(csv.DictReader(open(f"{work}/{name}.history.csv")))
    steps = {}
    for r in rows:
        steps.setdefault(int(r["step"]), {})[int(r["probe"])] = (float(r["ux"]), float(r["uy"]), float(r["uz"]))
    return steps
def timing(name):
    rows = [r for r in csv.DictReader(open(f"{work}/{name}/timings.csv")) if int(r["step"]) > 0]
    return 1e3 * sum(sum(float(r[k]) for k in ("blade_s", "topology_s", "assemble_s", "solve_s")) for r in rows) / len(rows)
def gap(name):
    return float(list(csv.DictReader(open(f"{work}/{name}/opening.csv")))[-1]["gap_volume"])
hist = {r[0]: history(r[0]) for r in runs}
ref = runs[-1][0]
steps = sorted(hist[ref])
probes = [p for p in hist[ref][0] if all(all(math.isfinite(c) for c in hist[n][s][p]) for n in hist for s in (0, steps[-1]))]
def error(name, chosen):
    num = den = 0.0
    for s in chosen:
        for p in probes:
            a, b = hist[name][s][p], hist[ref][s][p]
            num += sum((x - y) ** 2 for x, y in zip(a, b))
            den += sum(y * y for y in b)
    return math.sqrt(num / den)
with open(out, "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["run", "element", "tets", "nodes", "mass", "unknowns_end", "ms_per_step", "e_history", "e_end", "e_gap", "gap_volume", "probes"])
    for name, order, tets, mass, solver in runs:
        stdout = open(f"{work}/{name}.stdout.txt").read()
        mesh = re.search(r"mesh: (\d+) nodes, (\d+) Tet", stdout)
        unknowns = list(csv.DictReader(open(f"{work}/{name}/timings.csv")))[-1]["unknowns"]
        w.writerow([name, "Tet4" if order == "1" else "Tet10", mesh.group(2), mesh.group(1), mass, unknowns, f"{timing(name):.4g}",
                    f"{error(name, steps):.4g}", f"{error(name, steps[-1:]):.4g}", f"{abs(gap(name) - gap(ref)) / abs(gap(ref)):.4g}",
                    f"{gap(name):.6g}", len(probes)])
EOF
fi

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 1200,540 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "accuracy.png"
set datafile separator ","
set logscale xy
set grid lc rgb "#dddddd"
set key off
set xlabel "ms per step (one core, simulation only)"
set multiplot layout 1,2 title "07\\_liver: error against cost, the demo's cut (accuracy.csv; reference: the last row)" font ",12"
# Blue: lumped mass, red: consistent; circles Tet4, squares Tet10. Only the lumped runs are
# labelled: each consistent run lies on (or next to) its lumped twin.
set key bottom left opaque box font ",9"
point(el) = el eq "Tet4" ? 7 : 5
colour(m) = m eq "lumped" ? 0x1f77b4 : 0xd62728
label(r) = strcol("mass") eq "lumped" ? sprintf(" %s %dk", strcol("element"), int(column("tets") / 1000.0 + 0.5)) : ""
set ylabel "e_{history}: displacement at the probes, RMS over 2.5 s"
plot "accuracy.csv" using (column("ms_per_step")):(x = column("e_history"), x > 0 ? x : 1/0):(point(strcol("element"))):(colour(strcol("mass"))) \
       w p pt variable ps 1.6 lc rgb variable notitle, \
     "" using (column("ms_per_step")):(x = column("e_history"), x > 0 ? x : 1/0):(label(0)) w labels left font ",9" offset 0.6, 0.4 notitle, \
     NaN w p pt 7 ps 1.4 lc rgb "#1f77b4" t "Tet4, lumped", NaN w p pt 7 ps 1.4 lc rgb "#d62728" t "Tet4, consistent", \
     NaN w p pt 5 ps 1.4 lc rgb "#1f77b4" t "Tet10, lumped", NaN w p pt 5 ps 1.4 lc rgb "#d62728" t "Tet10, consistent"
set ylabel "e_{gap}: the wound's gap volume at 2.5 s"
unset key
plot "accuracy.csv" using (column("ms_per_step")):(x = column("e_gap"), x > 0 ? x : 1/0):(point(strcol("element"))):(colour(strcol("mass"))) \
       w p pt variable ps 1.6 lc rgb variable notitle, \
     "" using (column("ms_per_step")):(x = column("e_gap"), x > 0 ? x : 1/0):(label(0)) w labels left font ",9" offset 0.6, 0.4 notitle
unset multiplot
EOF
echo "accuracy.sh: wrote $here/accuracy.csv and accuracy.png"

python3 - "$here/accuracy.csv" "$here/accuracy.md" << 'EOF'
import csv, sys
rows = list(csv.DictReader(open(sys.argv[1])))
ref = rows[-1]
out = []
p = out.append
p("# Chapter 7: accuracy against cost (the demo's cut)")
p("")
p("![error against ms per step: Tet4 and Tet10, coarse and fine, lumped and consistent mass](accuracy.png)")
p("")
p("Made by `figures/07_liver/accuracy.sh` (`accuracy.csv`). Every run is the demo scene")
p("examples/07_liver_cut.json (2.5 s, 250 steps of 10 ms, the blade across the right lobe) with frames")
p("off, at the element, size and mass the row gives, every run with chapter 6's frozen step")
p("(`\"corotation\": \"frozen\"`; chapter 7's default, the checked step, costs about 2.3 times as much);")
p("the Tet10 runs with CHOLMOD, the Tet4 runs with 07_liver's default conjugate gradients (the script")
p("says why). The reference is the last row:")
p(f"{ref['element']}, {ref['tets']} tets, {ref['mass']} mass.")
p("")
p("- e_history: the RMS over the probes and all 251 steps of |u - u_ref|, over the RMS of |u_ref|;")
p(f"  {ref['probes']} probes, the points of a 9 x 7 x 5 grid over the liver's box that lie inside every run's mesh.")
p("- e_end: the same at the last step only.")
p("- e_gap: |V_gap - V_gap_ref| / V_gap_ref at the last step, V_gap the wound's gap volume (opening.csv).")
p("- ms per step: blade + topology + assemble + solve, wall clock, one run each, on the project's")
p("  2-core machine with other work running: a cost to compare runs by, within a factor of about 1.5.")
p("")
p("| run | element | tets | mass | unknowns at the end | ms per step | e_history | e_end | e_gap | gap volume (cm^3) |")
p("|---|---|---|---|---|---|---|---|---|---|")
for r in rows:
    p(f"| {r['run']} | {r['element']} | {r['tets']} | {r['mass']} | {r['unknowns_end']} | {float(r['ms_per_step']):.1f} | "
      f"{float(r['e_history']):.3f} | {float(r['e_end']):.3f} | {float(r['e_gap']):.3f} | {float(r['gap_volume']) * 1e6:.2f} |")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
print("\n".join(out))
EOF
