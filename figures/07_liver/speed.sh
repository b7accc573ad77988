#!/bin/bash
# Chapter 7's speed study: where the time of a step of 07_liver goes while the blade cuts, from
# 2k to 100k tets, on one core. Builds nothing: it runs build/release/bin/07_liver (build it first:
# cmake --build build/release --target 07_liver) on speed_scene.json (written here: the demo scene
# with the blade entering at once), reads each run's timings.csv and writes
#   speed.csv    one row per liver size (and the render runs' ms per frame),
#   speed.png    stacked bars: ms per cutting step in blade, topology, assemble, solve, render,
#   speed.md     the table, the goals and whether they are met, and how it was measured.
#
#   figures/07_liver/speed.sh [BUILD_DIR]      (default: build/release; about 6 minutes)
#   figures/07_liver/speed.sh --charts         (only redraw speed.png and speed.md from speed.csv)
#
# The numbers are wall times of steps: run it on a quiet machine (the load is recorded).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
command -v gnuplot > /dev/null || { echo "speed.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
# The sizes, the steps of each run (fewer at 100k: a step there costs about a second), and the
# sizes that also get a run with a frame drawn every step.
sizes=(2000 5000 10000 20000 50000 100000)
steps_of() { if [ "$1" -ge 100000 ]; then echo 40; else echo 100; fi; }
render_sizes=(10000 100000)
render_steps_of() { if [ "$1" -ge 100000 ]; then echo 20; else echo 60; fi; }

scene_json() { # steps render_every
  cat << EOF
{
  "name": "liver_speed",
  "mesh": {"liver": {"tets": 10000}, "order": 1},
  "material": {"young": 4000, "poisson": 0.45, "density": 1060},
  "model": "corotational",
  "gravity": [0, 0, -9.81],
  "dirichlet": [{"region": {"box": {"min": [-1, 0.045, -0.01], "max": [1, 1, 1]}}},
                {"region": {"box": {"min": [-1, -0.01, -1], "max": [1, 1, -0.03]}}}],
  "blade": {"path": [{"time": 0.05, "edge": [[0.11, -0.005, 0.09], [0.11, -0.005, 0.0]]},
                     {"time": 1.25, "edge": [[-0.04, -0.005, 0.09], [-0.04, -0.005, 0.0]]}]},
  "time": {"integrator": "newmark", "dt": 0.01, "steps": $1, "mass": "lumped", "rayleigh": [2, 0.01],
           "corotation": "frozen"},
  "output": {"every": 100000},
  "render": {"every": $2, "width": 960, "height": 720, "animation": false,
             "camera": {"azimuth": -100, "elevation": 40, "zoom": 1.3}}
}
EOF
}

if [ "${1:-}" != "--charts" ]; then
  build=${1:-$root/build/release}
  bin=$build/bin/07_liver
  [ -x "$bin" ] || { echo "speed.sh: $bin not found: cmake --build $build --target 07_liver" >&2; exit 1; }
  work=$root/output/figures_07_speed
  rm -rf "$work"
  mkdir -p "$work"
  scene_json 100 0 > "$here/speed_scene.json"
  export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
  pin=()
  command -v taskset > /dev/null && pin=(taskset -c "${KERF_STUDY_CORE:-0}")
  run() { # name tets steps render_every [prefix...]
    local name=$1 tets=$2 steps=$3 every=$4
    shift 4
    mkdir -p "$work/$name"
    scene_json "$steps" "$every" > "$work/$name/scene.json"
    cut -d' ' -f1 /proc/loadavg > "$work/$name/load_before"
    echo "speed.sh: $name: ${pin[*]} $* 07_liver --scene $work/$name/scene.json --tets $tets" >&2
    local timer=()
    [ -x /usr/bin/time ] && timer=(/usr/bin/time -f "%e %U %S" -o "$work/$name/cpu_time")
    "${pin[@]}" "${timer[@]}" "$@" "$bin" --scene "$work/$name/scene.json" --tets "$tets" --out "$work/$name" > "$work/$name/stdout.txt"
    cut -d' ' -f1 /proc/loadavg > "$work/$name/load_after"
  }
  # Three runs of each size: the step times of one run move by 10-15 % from run to run on this
  # shared machine (3 December 2026, five runs at 10k: 28.0 to 31.8 ms per cutting step), so the
  # table gives the run with the median cutting step and the spread of the three.
  # The three rounds go through every size in turn, so that a slow spell of the shared machine
  # (seen here: the same binary 35 % slower for minutes, with no load inside this machine) spreads
  # over the sizes instead of falling on all three runs of one.
  for r in 1 2 3; do
    for n in "${sizes[@]}"; do run "tets_${n}_run$r" "$n" "$(steps_of "$n")" 0; done
  done
  for n in "${render_sizes[@]}"; do run "render_$n" "$n" "$(render_steps_of "$n")" 1 xvfb-run -a; done
  lscpu | sed -n 's/^Model name: *//p' | head -1 > "$work/cpu"
  python3 - "$work" "$here/speed.csv" "${sizes[*]}" "${render_sizes[*]}" << 'EOF'
import csv, os, re, sys
work, out, sizes, render_sizes = sys.argv[1], sys.argv[2], sys.argv[3].split(), sys.argv[4].split()
parts = ["blade_s", "topology_s", "assemble_s", "solve_s"]

def read_run(name):
    folder = os.path.join(work, name)
    rows = list(csv.DictReader(open(os.path.join(folder, "timings.csv"))))
    rows = [r for r in rows if int(r["step"]) > 0]
    stdout = open(os.path.join(folder, "stdout.txt")).read()
    mesh = re.search(r"mesh: (\d+) nodes, (\d+) Tet", stdout)
    setup = re.search(r"setup: ([0-9.e+-]+) s", stdout)
    wall = re.search(r"stepped \d+ steps in ([0-9.e+-]+) s", stdout)
    load = [open(os.path.join(folder, f)).read().strip() for f in ("load_before", "load_after")]
    # The share of a core the run had: processor time (user + system) over wall time of the whole run.
    share = float("nan")
    if os.path.exists(os.path.join(folder, "cpu_time")):
        elapsed, user, system = map(float, open(os.path.join(folder, "cpu_time")).read().split()[-3:])
        share = (user + system) / elapsed
    load.append(share)
    return rows, int(mesh.group(1)), int(mesh.group(2)), float(setup.group(1)), float(wall.group(1)), load

def ms(rows, key=None):
    if not rows: return float("nan")
    return 1e3 * sum(sum(float(r[k]) for k in parts) if key is None else float(r[key]) for r in rows) / len(rows)

def size_row(n, name):
    rows, nodes, tets, setup, wall, load = read_run(name)
    first_cut = next(i for i, r in enumerate(rows) if r["topology_changed"] == "1")
    cutting = rows[first_cut:]
    topo = [r for r in cutting if r["topology_changed"] == "1"]
    plain = [r for r in cutting if r["topology_changed"] == "0"]
    slowest = max(1e3 * sum(float(r[k]) for k in parts) for r in topo)
    row = {"target": n, "tets": tets, "nodes": nodes, "steps": len(rows), "cutting_steps": len(cutting),
           "topology_changes": len(topo), "unknowns_uncut": rows[0]["unknowns"], "unknowns_end": rows[-1]["unknowns"],
           "crossed_tets_end": rows[-1]["crossed_tets"],
           "uncut_ms": ms(rows[1:first_cut]), "cutting_ms": ms(cutting), "no_topology_ms": ms(plain), "topology_step_ms": ms(topo),
           "slowest_topology_ms": slowest}
    for k in parts: row[k.replace("_s", "_ms")] = ms(cutting, k)
    row.update({"render_ms_per_frame": float("nan"), "render_frames": 0, "setup_s": setup, "wall_s": wall,
                "load_before": load[0], "load_after": load[1], "core_share": load[2],
                "cutting_ms_idle_estimate": row["cutting_ms"] * load[2]})
    return row

table = []
for n in sizes:
    runs = sorted((size_row(n, f"tets_{n}_run{r}") for r in (1, 2, 3)), key=lambda row: row["cutting_ms"])
    row = runs[1]  # the median run
    row["cutting_ms_min"], row["cutting_ms_max"] = runs[0]["cutting_ms"], runs[-1]["cutting_ms"]
    if n in render_sizes:
        rrows, _, _, _, _, rload = read_run("render_" + n)
        frames = [float(r["render_s"]) for r in rrows if float(r["render_s"]) > 0]
        row["render_ms_per_frame"] = 1e3 * sum(frames) / len(frames)
        row["render_frames"] = len(frames)
        row["render_max_ms"] = 1e3 * max(frames)
        row["render_load"] = rload[0] + "/" + rload[1]
    table.append(row)
keys = list(table[0].keys()) + [k for k in ("render_max_ms", "render_load") if k not in table[0]]
with open(out, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=keys, restval="nan")
    w.writeheader()
    for row in table:
        w.writerow({k: (f"{v:.4g}" if isinstance(v, float) else v) for k, v in row.items()})
EOF
  cp "$work/cpu" "$here/speed_cpu.txt"
fi

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 1200,560 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "speed.png"
set datafile separator ","
set style data histograms
set style histogram rowstacked
set style fill solid 0.85 border rgb "#333333"
set boxwidth 0.6
set grid ytics lc rgb "#dddddd"
set key top left opaque box font ",10"
set offsets 0, 0, graph 0.55, 0
set ylabel "ms per step while the blade cuts (wall clock, one core)"
set xlabel "tets (liver, Tet4)"
set multiplot layout 1,2 title "07\\_liver: where a cutting step goes (speed.csv; render: one 960x720 frame, measured at 10k and 100k)" font ",12"
set yrange [0:*]
plot "speed.csv" every ::0::3 using (column("blade_ms")):xtic(2) t "blade" lc rgb "#9467bd", \
     "" every ::0::3 using (column("topology_ms")) t "topology" lc rgb "#d62728", \
     "" every ::0::3 using (column("assemble_ms")) t "assemble" lc rgb "#1f77b4", \
     "" every ::0::3 using (column("solve_ms")) t "solve" lc rgb "#2ca02c", \
     "" every ::0::3 using (x = column("render_ms_per_frame"), x == x ? x : 0) t "render (a frame)" lc rgb "#ff7f0e", \
     10 w l dt 2 lw 2 lc rgb "#000000" t "goal at 10k: 10 ms per cutting step", \
     16 w l dt 3 lw 2 lc rgb "#d62728" t "goal: 16 ms per topology step"
unset key
plot "speed.csv" every ::4::5 using (column("blade_ms")):xtic(2) t "blade" lc rgb "#9467bd", \
     "" every ::4::5 using (column("topology_ms")) t "topology" lc rgb "#d62728", \
     "" every ::4::5 using (column("assemble_ms")) t "assemble" lc rgb "#1f77b4", \
     "" every ::4::5 using (column("solve_ms")) t "solve" lc rgb "#2ca02c", \
     "" every ::4::5 using (x = column("render_ms_per_frame"), x == x ? x : 0) t "render (a frame)" lc rgb "#ff7f0e"
unset multiplot
EOF

python3 - "$here/speed.csv" "$here/speed.md" "$(cat "$here/speed_cpu.txt" 2> /dev/null || echo unknown)" << 'EOF'
import csv, math, sys
rows = list(csv.DictReader(open(sys.argv[1])))
cpu = sys.argv[3]
f = lambda r, k: float(r[k])
by = {r["target"]: r for r in rows}
out = []
p = out.append
p("# Chapter 7: the speed of a cutting step (07_liver, one core)")
p("")
p("![ms per cutting step by part, 2k to 100k tets](speed.png)")
p("")
p("Made by")
p("")
p("    figures/07_liver/speed.sh        # runs build/release/bin/07_liver 20 times, about 6 minutes")
p("")
p("(`speed.csv`; the scene is `speed_scene.json`, which the script writes: the demo scene")
p("examples/07_liver_cut.json with the blade already beside the organ at t = 0.05 s, at x = 0.11 m,")
p("moving at the demo's 12.5 cm/s along -x, so that it cuts from the first steps on; no frames and")
p("no .vtu output in the timed runs).")
p("")
p(f"- Machine: `{cpu}`, 2 cores shared with other work. Each run is pinned to core 0 (`taskset -c 0`)")
p("  with `OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1`. The load average (1 min)")
p("  before and after each run is in `speed.csv` (`load_before`, `load_after`): on 2 cores a load above")
p("  1 means other processes took turns on our core. *Share of a core* is the run's processor time")
p("  (user + system, /usr/bin/time) over its wall time: below 1, the wall times here are longer than on an")
p("  idle core, by about 1 / share (the share is of the whole run, setup included, so this is an estimate).")
p("- Three rounds over all sizes; a row is the run whose cutting step is the median of its size's three, and the")
p("  cutting-step column gives the three runs' range (the same program on the same scene varies by 10-15 %")
p("  from run to run on this shared machine). The times are of `timings.csv` (steady clock, per step). A *cutting step* is")
p("  any step from the first topology change on (the blade is in the tissue in all of them: it stops")
p("  at x = -0.04 m at 1.25 s, after the last step). *ms per step* is blade + topology + assemble +")
p("  solve (the simulation), without render and output.")
p("- A step solves, then the blade's next edge cuts the body it moved; if the edge crossed a tet, the")
p("  model is rebuilt and assembled once at the new state, which closes the step's energy and starts the")
p("  next step. A row *with* a topology change is such a step: its solve, the rebuild and that one")
p("  assembly. The next step's solve, the first on the new model, also finds the new matrix pattern;")
p("  it is in its own row. cuts.csv's check that the energies are unchanged (the old model's W) is")
p("  output, not simulation.")
p("- The 100k runs have 40 steps (0.4 s, the first 4 cm of the cut), the others 100 steps (1 s,")
p("  about 11 cm): its cut is shorter, so its topology steps rebuild a model with fewer enrichments.")
p("- Render: separate runs with a frame every step, 960 x 720, under `xvfb-run -a` (Mesa, on the")
p("  same core), 60 steps at 10k and 20 at 100k; the time of a frame is moving the 3 mm visual")
p("  surface (10542 triangles), dropping its torn triangles, the cut faces, drawing, and writing")
p("  the PNG.")
p("")
p("## Measured")
p("")
p("| tets | steps (cutting) | topology changes | unknowns uncut → end | uncut step (ms) | cutting step (ms; 3 runs' range) | without topology change (ms) | with one (ms) | slowest topology step (ms) | blade / topology / assemble / solve (ms per cutting step) | render (ms per frame) | load before/after | share of a core |")
p("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|---:|---|---:|")
for r in rows:
    render = "—" if r["render_ms_per_frame"] == "nan" else f"{f(r, 'render_ms_per_frame'):.1f} ({r['render_frames']} frames, max {f(r, 'render_max_ms'):.1f})"
    p(f"| {int(r['tets']):,} | {r['steps']} ({r['cutting_steps']}) | {r['topology_changes']} | {int(r['unknowns_uncut']):,} → {int(r['unknowns_end']):,} | "
      f"{f(r, 'uncut_ms'):.1f} | {f(r, 'cutting_ms'):.1f} ({f(r, 'cutting_ms_min'):.1f}–{f(r, 'cutting_ms_max'):.1f}) | {f(r, 'no_topology_ms'):.1f} | {f(r, 'topology_step_ms'):.1f} | {f(r, 'slowest_topology_ms'):.1f} | "
      f"{f(r, 'blade_ms'):.2f} / {f(r, 'topology_ms'):.1f} / {f(r, 'assemble_ms'):.1f} / {f(r, 'solve_ms'):.1f} | {render} | {r['load_before']}/{r['load_after']} | {f(r, 'core_share'):.2f} |")
p("")
p("## The goals")
p("")
ten = by.get("10000")
if ten:
    cut = f(ten, "cutting_ms"); plain = f(ten, "no_topology_ms"); topo = f(ten, "topology_step_ms"); slow = f(ten, "slowest_topology_ms")
    frame = f(ten, "render_ms_per_frame")
    verdict = lambda v, goal: "met" if v <= goal else f"missed by a factor {v / goal:.1f}"
    p(f"- **10k tets, at most 10 ms per step with the blade cutting**: {cut:.1f} ms per cutting step on average "
      f"(the median of three runs; {f(ten, 'cutting_ms_min'):.1f} in the fastest), "
      f"{verdict(cut, 10)}; the steps without a topology change alone take {plain:.1f} ms ({verdict(plain, 10)}).")
    if not math.isnan(frame):
        p(f"  With a frame drawn every step ({frame:.1f} ms) a cutting step with its picture takes {cut + frame:.1f} ms, {verdict(cut + frame, 10)}.")
    p(f"- **A topology-changing step at most 16 ms** (10k): {topo:.1f} ms on average over {ten['topology_changes']} such steps, "
      f"the slowest {slow:.1f} ms: {verdict(topo, 16)} on average, {verdict(slow, 16)} for the slowest.")
twenty = by.get("20000")
if twenty:
    k = 1375.0
    c = f(twenty, "cutting_ms")
    p(f"- **Koschier et al.'s bunny, about 18.5k tets, 1.375 s per step on 4 cores** (i7-6700HQ, backward Euler,")
    p(f"  Newton, PARDISO; 47 % of the time in cutting and enriching): our {int(twenty['tets']):,}-tet liver takes "
      f"{c:.0f} ms per cutting step on one core, {k / c:.0f} times less wall time per step")
    p("  (different scenes, methods and machines: Koschier re-cuts along a general cut surface with his own")
    p("  quadrature and a direct solver; here one frozen-rotation Newmark step, CG-Jacobi, and a rebuild")
    p("  when a tet becomes crossed).")
p("")
p("## What it says")
p("")
share = lambda r, k: 100 * f(r, k) / f(r, "cutting_ms")
for r in rows:
    if r["target"] in ("10000", "100000"):
        p(f"- At {int(r['tets']):,} tets a cutting step is {share(r, 'topology_ms'):.0f} % topology, {share(r, 'assemble_ms'):.0f} % assembly, "
          f"{share(r, 'solve_ms'):.0f} % solve and {share(r, 'blade_ms'):.1f} % blade (pull-back, sheet, crossing test); "
          f"{r['topology_changes']} of its {r['cutting_steps']} cutting steps changed the topology.")
small = rows[0]
# The largest mesh with steps that changed no topology (at 100k every cutting step may change it).
large = [r for r in rows if f(r, "no_topology_ms") == f(r, "no_topology_ms")][-1]
grow = f(large, "no_topology_ms") / f(small, "no_topology_ms")
p(f"- From {int(small['tets']):,} to {int(large['tets']):,} tets ({int(large['tets']) / int(small['tets']):.0f} times) a step without a topology "
  f"change costs {grow:.0f} times more, a topology step {f(large, 'topology_step_ms') / f(small, 'topology_step_ms'):.0f} times more:")
p("  CG-Jacobi needs more iterations on a finer mesh, and of a rebuild the new model's one assembly, the lumping")
p("  and the pieces' copy still pass over the whole mesh (the model's points, the split tets' masses, the glue and")
p("  the pattern are rebuilt only where the cut changed).")
p("- The blade's share (pulling the edge back, growing the sheet, the semi-progressive crossing test) is small at")
p("  every size, as figures/07_liver/blade_sweep.md measured for the crossing test alone.")
p("- These are the timings of main.cpp as of the commit that made them; the program is being optimised, and")
p("  `figures/07_liver/speed.sh` remakes every number here.")
open(sys.argv[2], "w").write("\n".join(out) + "\n")
EOF
echo "wrote $here/speed.csv, speed.png and speed.md"
