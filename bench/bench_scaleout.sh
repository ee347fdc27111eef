#!/usr/bin/env bash
# Scale-out benchmark (docs/SCALING.md): ratios measured in one run on this machine, printed as
# JSON on stdout. Never run by ctest.
#   bench/bench_scaleout.sh [BUILD_DIR] [--large]
# 1. The same bake of the open-world scene (data/tools/make_open_world.py) as 1 process × 1 thread
#    and as mpirun -np 2 × 1 thread: speed-up (goal >= 0.9 × 2).
# 2. The same bake as shards 0/2 and 1/2, then baker merge: merge time ÷ one-process bake time
#    (goal <= 2 %).
# 3. Peak memory of a bake at 1×, 8× and 64× the probes of the first (spacing ÷ 2 and ÷ 4).
# 4. With --large: >= 1e7 probes of the open world over two MPI ranks: probes/s and peak memory
#    per rank (runs for minutes).
set -euo pipefail
build=${1:-build}
large=${2:-}
baker=$(cd "$build" && pwd)/baker
source=$(cd "$(dirname "$0")/.." && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
python3 "$source/data/tools/make_open_world.py" "$work" > /dev/null
scene=$work/open_world.gltf
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
options=(--rays 32 --bounces 1 --basis sh-l2 --sky 0.6,0.7,0.9 --quiet --json)
seconds() { python3 -c 'import sys,time; print(time.monotonic())'; }
field() { python3 -c "import json,sys; d=json.load(open('$1')); print(d$2)"; }

spacing=8
t0=$(seconds); "$baker" "$scene" "${options[@]}" --spacing $spacing --threads 1 --out one.vdb > one.json; t1=$(seconds)
mpirun --oversubscribe -np 2 "$baker" "$scene" "${options[@]}" --spacing $spacing --threads 1 --mpi --out mpi.vdb > mpi.json
t2=$(seconds)
cmp one.vdb mpi.vdb
"$baker" "$scene" "${options[@]}" --spacing $spacing --threads 1 --shard 0/2 --out p0.vdb > p0.json
"$baker" "$scene" "${options[@]}" --spacing $spacing --threads 1 --shard 1/2 --out p1.vdb > p1.json
t3=$(seconds); "$baker" merge merged.vdb p1.vdb p0.vdb > /dev/null; t4=$(seconds)
cmp one.vdb merged.vdb

memory=()
for s in 8 4 2; do
  "$baker" "$scene" --rays 8 --bounces 0 --basis sh-l2 --sky 0.6,0.7,0.9 --quiet --json --spacing $s --out m.vdb > m.json
  memory+=("$(field m.json "['probes']"):$(field m.json "['peak_memory_bytes']")")
done

python3 - "$t0" "$t1" "$t2" "$t3" "$t4" "${memory[@]}" <<'PY'
import json, os, sys
t0, t1, t2, t3, t4 = map(float, sys.argv[1:6])
one = json.load(open("one.json")); mpi = json.load(open("mpi.json"))
memory = [dict(zip(("probes", "peak_memory_bytes"), map(int, m.split(":")))) for m in sys.argv[6:]]
print(json.dumps({
    "machine": {"cores": os.cpu_count()},
    "scene": "open_world (data/tools/make_open_world.py, 6000 instances, 1 km)",
    "probes": one["probes"],
    "one_process_one_thread_seconds": t1 - t0,
    "mpi_two_ranks_one_thread_seconds": t2 - t1,
    "mpi_speedup": (t1 - t0) / (t2 - t1),
    "mpi_speedup_goal": 1.8,
    "merge_seconds": t4 - t3,
    "merge_over_one_process_bake": (t4 - t3) / (t1 - t0),
    "merge_over_bake_goal": 0.02,
    "peak_memory_by_probes": memory,
    "bytes_per_probe_growth": [(b["peak_memory_bytes"] - memory[0]["peak_memory_bytes"]) / max(1, b["probes"] - memory[0]["probes"]) for b in memory[1:]],
}, indent=2))
PY

if [ "$large" = "--large" ]; then
  start=$(seconds)
  mpirun --oversubscribe -np 2 "$baker" "$scene" --rays 16 --bounces 1 --basis sh-l1 --sky 0.6,0.7,0.9 --quiet --json \
    --spacing 1.6 --mpi --out large.vdb > large.json
  end=$(seconds)
  python3 - "$start" "$end" <<'PY'
import json, sys
start, end = map(float, sys.argv[1:3])
r = json.load(open("large.json"))
print(json.dumps({"large": {
    "probes": r["probes"], "ranks": r["ranks"], "seconds": end - start,
    "probes_per_second": r["probes"] / (end - start),
    "per_rank": [{"rank": p["rank"], "probes": p["probes"], "probes_per_second": p["probes"] / p["bake_seconds"],
                  "peak_memory_bytes": p["peak_memory_bytes"]} for p in r["per_rank"]],
    "gather_seconds": r["seconds"]["gather"], "write_seconds": r["seconds"]["write"]}}, indent=2))
PY
fi
