#!/bin/bash
# Chapter 8's speed study: where the time of a cutting step of 08_real_time goes, from 2k to 100k
# tets, one core, beside chapter 7's step (07_liver, its default checked step) on the same scene:
# the demo's liver with the blade entering at once (it cuts from the first steps and is still in
# the tissue at the last), no frames, no output but the logs. Runs build/release/bin/08_real_time
# and 07_liver (build them first), reads each run's timings.csv and the whole process's times
# (/usr/bin/time: meshing and setup included), and writes here
#   speed.csv   one row a run: program, tets, steps, ms a step by part, the slowest step that
#               changed the topology, the process's wall and processor seconds
#   real_time_speed.png   ms a step against tets, chapter 8 by part (stacked) and chapter 7's total
#   speed.md    the table and the goals
#
#   figures/08_real_time/speed.sh [BUILD_DIR]     (default: build/release; about 6 minutes)
#
# The numbers are wall times: run it on a quiet machine. Each run is pinned to one core.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
build=$(cd "${1:-$root/build/release}" && pwd)
command -v gnuplot > /dev/null || { echo "speed.sh: gnuplot not found (apt-get install gnuplot-nox)" >&2; exit 1; }
for program in 07_liver 08_real_time; do
  [ -x "$build/bin/$program" ] || { echo "speed.sh: $build/bin/$program not found: cmake --build $build --target $program" >&2; exit 1; }
done
work=$root/output/figures_08_speed
rm -rf "$work"
mkdir -p "$work"
export OPENBLAS_NUM_THREADS=1 OMP_NUM_THREADS=1 OMP_THREAD_LIMIT=1
pin=()
command -v taskset > /dev/null && pin=(taskset -c "${KERF_STUDY_CORE:-0}")
steps_of() { if [ "$1" -ge 100000 ]; then echo 40; else echo 100; fi; }

for tets in 2000 10000 30000 100000; do
  steps=$(steps_of "$tets")
  python3 - "$root/examples/07_liver_cut.json" "$work/scene_$tets.json" "$tets" "$steps" << 'EOF'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["name"] = "liver_speed"
scene["mesh"]["liver"]["tets"] = int(sys.argv[3])
scene["time"]["steps"] = int(sys.argv[4])
scene["blade"]["path"] = [{"time": 0.05, "edge": [[0.11, -0.005, 0.09], [0.11, -0.005, 0.0]]},
                          {"time": 1.25, "edge": [[-0.04, -0.005, 0.09], [-0.04, -0.005, 0.0]]}]
scene["render"] = {"every": 0}
scene["output"] = {"every": 100000}
json.dump(scene, open(sys.argv[2], "w"), indent=2)
EOF
  for program in 08_real_time 07_liver; do
    name=${program}_$tets
    echo "speed.sh: $name ($steps steps)"
    /usr/bin/time -f "%e %U %S" -o "$work/$name.time" "${pin[@]}" "$build/bin/$program" --quiet --scene "$work/scene_$tets.json" \
      --out "$work/$name" > /dev/null
  done
done

python3 - "$work" "$here/speed.csv" "$here/speed.md" << 'EOF'
import csv, sys
work, out_csv, out_md = sys.argv[1:]
rows = []
for tets in (2000, 10000, 30000, 100000):
    for program in ("08_real_time", "07_liver"):
        name = f"{program}_{tets}"
        timings = [r for r in csv.DictReader(open(f"{work}/{name}/timings.csv")) if int(r["step"]) > 0]
        wall, user, system = (float(x) for x in open(f"{work}/{name}.time").read().split())
        n = len(timings)
        if program == "08_real_time":
            part = lambda k: sum(float(r[k]) for r in timings) / n
            parts = {"blade": part("blade_ms"), "topology": part("topology_ms"), "local": part("local_ms"), "global": part("global_ms"),
                     "other": part("other_ms"), "output": part("output_ms")}
            simulate = [float(r["simulate_ms"]) for r in timings]
            changed = [float(r["simulate_ms"]) for r in timings if r["topology_changed"] == "1"]
        else:
            part = lambda k: 1e3 * sum(float(r[k]) for r in timings) / n
            parts = {"blade": part("blade_s"), "topology": part("topology_s"), "local": part("assemble_s"), "global": part("solve_s"),
                     "other": 0.0, "output": part("output_s")}
            simulate = [1e3 * (float(r["blade_s"]) + float(r["topology_s"]) + float(r["assemble_s"]) + float(r["solve_s"])) for r in timings]
            # chapter 7 books a change of topology in the row of the step before it; its slowest
            # topology step is that row's.
            changed = [s for s, r in zip(simulate, timings) if r["topology_changed"] == "1"]
        rows.append({"program": program, "tets": tets, "steps": n, "ms_per_step": round(sum(simulate) / n, 3),
                     **{f"{k}_ms": round(v, 3) for k, v in parts.items()},
                     "slowest_topology_step_ms": round(max(changed) if changed else 0.0, 3), "changes": len(changed),
                     "process_wall_s": wall, "process_cpu_s": round(user + system, 2)})
with open(out_csv, "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
with open(out_md, "w") as f:
    f.write("# Chapter 8: the speed of a cutting step, 2k to 100k tets\n\n![ms a step by part](real_time_speed.png)\n\nMade by\n\n"
            "    figures/08_real_time/speed.sh     # about 6 minutes\n\n"
            "One core (each run pinned to core 0, OpenBLAS on one thread); the blade cuts from the first steps. For chapter 8 the parts "
            "are timings.csv's: blade, topology (the new body, the transfer, the grown factor), local (the passes over the pieces), "
            "global (the solves), other (vector work); output (energy.csv, opening.csv, cuts.csv's checks and the last .vtu) is apart "
            "from ms a step, which is the simulation's; for chapter 7, assemble stands in the local column and solve in the global. "
            "Process: the whole run, meshing and setup included (/usr/bin/time). Goals at 10k tets: 2 ms a step, 6 ms for the "
            "slowest step that changes the topology; at 100k: 30 ms a step.\n\n"
            "| program | tets | steps | ms a step | blade | topology | local | global | other | output | slowest topology step (ms) | changes | process wall (s) | process cpu (s) |\n"
            "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n")
    for r in rows:
        f.write(f"| {r['program']} | {r['tets']} | {r['steps']} | {r['ms_per_step']} | {r['blade_ms']} | {r['topology_ms']} | {r['local_ms']} | "
                f"{r['global_ms']} | {r['other_ms']} | {r['output_ms']} | {r['slowest_topology_step_ms']} | {r['changes']} | {r['process_wall_s']} | {r['process_cpu_s']} |\n")
EOF
cat "$here/speed.md"

cd "$here"
gnuplot << 'EOF'
set terminal pngcairo size 1200,520 enhanced font "DejaVu Sans,11" linewidth 1.2
set output "real_time_speed.png"
set datafile separator ","
set multiplot layout 1,2 title "08\\_real\\_time on one core, the blade cutting (speed.csv)" font ",12"
set grid lc rgb "#dddddd"
set key top left opaque box font ",9"
# Left: chapter 8's step by part, stacked, per size.
set style data histograms
set style histogram rowstacked
set style fill solid 0.85 border -1
set boxwidth 0.6
set ylabel "ms a cutting step"
set title "chapter 8: where a step's time goes"
plot "< awk -F, 'NR == 1 || $1 == \"08_real_time\"' speed.csv" using "blade_ms":xtic(sprintf("%dk", column("tets") / 1000)) t "blade" lc rgb "#9467bd", \
     "" using "topology_ms" t "topology" lc rgb "#ff7f0e", "" using "local_ms" t "local (pieces)" lc rgb "#1f77b4", \
     "" using "global_ms" t "global (solves)" lc rgb "#2ca02c", "" using "other_ms" t "other" lc rgb "#7f7f7f", \
     "" using "output_ms" t "output (logs)" lc rgb "#bcbd22"
# Right: ms a step against tets, both chapters, and the goals.
set style data linespoints
set logscale xy
set xlabel "liver tets"
set ylabel "ms a cutting step"
set title "chapter 8 beside chapter 7, and the goals"
ch8(c) = strcol("program") eq "08_real_time" ? column(c) : 1/0
ch7(c) = strcol("program") eq "07_liver" ? column(c) : 1/0
plot "speed.csv" using "tets":(ch8("ms_per_step")) w lp pt 7 ps 1.3 lc rgb "#1f77b4" t "chapter 8 (4 iterations a step)", \
     "" using "tets":(ch7("ms_per_step")) w lp pt 5 ps 1.3 lc rgb "#d62728" t "chapter 7 (checked step)", \
     "-" using 1:2 w p pt 9 ps 2 lc rgb "#000000" t "goals: 2 ms at 10k, 30 ms at 100k"
10000,2
100000,30
e
unset multiplot
EOF
echo "wrote $here/speed.csv, speed.md, real_time_speed.png"
