#!/usr/bin/env bash
# Scale-out benchmark (docs/SCALING.md): ratios measured in one run on this machine, printed as
# JSON on stdout. Never run by ctest.
#   bench/bench_scaleout.sh [BUILD_DIR] [--large]
# 1. A bake of the open-world scene (data/tools/make_open_world.py) as a studio runs it nightly
#    (--quality draft, the default 3 bounces) under mpirun as 1 rank and as 2 ranks, 1 thread
#    each, alternated; the fastest of each (this machine is shared and noisy), and the ratio of
#    each adjacent pair: speed-up, goal >= 0.9 × 2. Ranks are not bound to cores: on this 2-core VM a bound rank cannot leave a core
#    the system is also using, which made one rank up to 25 % slower than the other.
# 2. The same bake as shards 0/2 and 1/2, then baker merge: merge time ÷ the 1-rank bake's time,
#    goal <= 2 %; and the same for a bake of 32 rays and 1 bounce at 4× the probes, where the
#    merge (reading the parts and writing what the bake writes) weighs most.
# 3. Peak memory of one-process bakes at 1×, 8× and 64× the probes of the first (spacing ÷ 2, ÷ 4),
#    of single shards of the 64× bake cut into 64, and of merging the 8× bake from 8 parts.
# 4. With --large: >= 1e7 probes of the open world over two MPI ranks: probes/s and peak memory
#    per rank (runs for minutes).
# Environment: BAKER_BENCH_SPACING (default 16), BAKER_BENCH_REPEATS (default 3).
set -euo pipefail
build=${1:-build}
large=${2:-}
baker=$(cd "$build" && pwd)/baker
source=$(cd "$(dirname "$0")/.." && pwd)
spacing=${BAKER_BENCH_SPACING:-16}
repeats=${BAKER_BENCH_REPEATS:-3}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work"
python3 "$source/data/tools/make_open_world.py" "$work" > /dev/null
scene=$work/open_world.gltf
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
sky=(--sky 0.6,0.7,0.9 --quiet --json)
options=(--quality draft --basis sh-l2 "${sky[@]}" --spacing "$spacing")
cheap=(--rays 32 --bounces 1 --basis sh-l2 "${sky[@]}" --spacing "$(python3 -c "print($spacing / 4 ** (1 / 3))")")
now() { python3 -c 'import time; print(time.monotonic())'; }
field() { python3 -c "import json; print(json.load(open('$1'))$2)"; }
elapsed() { python3 -c "print($2 - $1)"; }
record() { echo "$1 $2" >> times.txt; }

# 1. Ranks, alternated so that a slow spell of the machine hits both.
for ((r = 0; r < repeats; ++r)); do
  for ranks in 1 2; do
    t0=$(now)
    mpirun --oversubscribe --bind-to none -np $ranks "$baker" "$scene" "${options[@]}" --threads 1 --mpi --out "mpi$ranks.vdb" \
      > "mpi$ranks.json"
    record "ranks$ranks" "$(elapsed "$t0" "$(now)")"
  done
done
cmp mpi1.vdb mpi2.vdb

# 2. Parts, then the merge (timed alone, repeated); the cheap bake's one-process time once.
"$baker" "$scene" "${options[@]}" --shard 0/2 --out p0.vdb > /dev/null
"$baker" "$scene" "${options[@]}" --shard 1/2 --out p1.vdb > /dev/null
t0=$(now)
"$baker" "$scene" "${cheap[@]}" --threads 1 --out cheap.vdb > cheap.json
record cheap_bake "$(elapsed "$t0" "$(now)")"
"$baker" "$scene" "${cheap[@]}" --shard 0/2 --out c0.vdb > /dev/null
"$baker" "$scene" "${cheap[@]}" --shard 1/2 --out c1.vdb > /dev/null
for ((r = 0; r < repeats + 1; ++r)); do
  t0=$(now)
  "$baker" merge merged.vdb p1.vdb p0.vdb > /dev/null
  record merge "$(elapsed "$t0" "$(now)")"
  t0=$(now)
  "$baker" merge cheap_merged.vdb c1.vdb c0.vdb > /dev/null
  record cheap_merge "$(elapsed "$t0" "$(now)")"
done
cmp mpi1.vdb merged.vdb
cmp cheap.vdb cheap_merged.vdb

# 3. Memory against probes: the whole bake, single shards, and a merge.
light=(--rays 8 --bounces 0 --basis sh-l2 "${sky[@]}")
for s in 8 4 2; do
  "$baker" "$scene" "${light[@]}" --spacing $s --out m.vdb > m.json
  record "whole_$s" "$(field m.json "['probes']"):$(field m.json "['peak_memory_bytes']")"
done
for k in 0 32; do
  "$baker" "$scene" "${light[@]}" --spacing 2 --shard $k/64 --out s.vdb > s.json
  record "shard_${k}_of_64" "$(field s.json "['probes']"):$(field s.json "['peak_memory_bytes']")"
done
for k in 0 1 2 3 4 5 6 7; do "$baker" "$scene" "${light[@]}" --spacing 4 --shard $k/8 --out "q$k.vdb" > /dev/null; done
"$baker" merge q.vdb q*.vdb --json > q.json
record merge_of_8 "$(field q.json "['probes']"):$(field q.json "['peak_memory_bytes']")"

python3 - <<'PY'
import json, os
times = {}
for line in open("times.txt"):
    key, value = line.split()
    times.setdefault(key, []).append(value)
best = lambda key: min(map(float, times[key]))
memory = lambda key: dict(zip(("probes", "peak_memory_bytes"), map(int, times[key][0].split(":"))))
one, two = best("ranks1"), best("ranks2")
mpi2 = json.load(open("mpi2.json"))
whole = [memory(f"whole_{s}") for s in (8, 4, 2)]
growth = [(b["peak_memory_bytes"] - whole[0]["peak_memory_bytes"]) / (b["probes"] - whole[0]["probes"])
          for b in whole[1:]]
print(json.dumps({
    "machine": {"cores": os.cpu_count()},
    "scene": "open_world (data/tools/make_open_world.py, 6000 instances, 1 km)",
    "probes": mpi2["probes"],
    "repeats": len(times["ranks1"]),
    "one_rank_one_thread_seconds": one,
    "two_ranks_one_thread_seconds": two,
    "two_ranks_speedup": one / two,
    "two_ranks_speedup_goal": 1.8,
    "two_ranks_speedup_of_each_pair": [float(a) / float(b) for a, b in zip(times["ranks1"], times["ranks2"])],
    "per_rank_bake_seconds": [r["bake_seconds"] for r in mpi2["per_rank"]],
    "per_rank_probes": [r["probes"] for r in mpi2["per_rank"]],
    "merge_seconds": best("merge"),
    "merge_over_one_rank_bake": best("merge") / one,
    "merge_over_bake_goal": 0.02,
    "cheap_bake": {"probes": json.load(open("cheap.json"))["probes"], "options": "--rays 32 --bounces 1",
                   "one_process_one_thread_seconds": best("cheap_bake"), "merge_seconds": best("cheap_merge"),
                   "merge_over_bake": best("cheap_merge") / best("cheap_bake")},
    "memory": {
        "whole_bake_1x_8x_64x": whole,
        "whole_bake_bytes_per_added_probe": growth,
        "one_shard_of_64_at_64x": [memory("shard_0_of_64"), memory("shard_32_of_64")],
        "merge_of_8_parts_at_8x": memory("merge_of_8"),
    },
}, indent=2))
PY

if [ "$large" = "--large" ]; then
  t0=$(now)
  mpirun --oversubscribe --bind-to none -np 2 "$baker" "$scene" --rays 16 --bounces 1 --basis sh-l1 "${sky[@]}" --spacing 1.6 \
    --mpi --out large.vdb > large.json
  record large "$(elapsed "$t0" "$(now)")"
  python3 - <<'PY'
import json
seconds = float([l.split()[1] for l in open("times.txt") if l.startswith("large ")][0])
r = json.load(open("large.json"))
print(json.dumps({"large": {
    "probes": r["probes"], "ranks": r["ranks"], "seconds": seconds,
    "probes_per_second": r["probes"] / seconds,
    "per_rank": [{"rank": p["rank"], "probes": p["probes"], "probes_per_second": p["probes"] / p["bake_seconds"],
                  "peak_memory_bytes": p["peak_memory_bytes"]} for p in r["per_rank"]],
    "rank_0_peak_memory_bytes_after_writing": r["peak_memory_bytes"],
    "gather_seconds": r["seconds"]["gather"], "write_seconds": r["seconds"]["write"]}}, indent=2))
PY
fi
