#!/usr/bin/env bash
# Regenerates docs/adaptive/report.md: adaptive placement against a uniform grid at its finest
# spacing (bench/bench_adaptive) on the bundled room, the furnished room and a 200 m tile of the
# open world, plus the probe counts of the whole 1 km open world from the plan (--dry-run).
# About 25 minutes on 2 cores.
#
#   scripts/adaptive_report.sh
set -euo pipefail
cd "$(dirname "$0")/.."
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 data/tools/make_furnished_room.py "$work/furnished" > /dev/null
python3 data/tools/make_open_world.py "$work/world" > /dev/null
python3 data/tools/make_open_world.py "$work/tile" --size 200 --instances 240 > /dev/null

# scene, spacing, rays, bounces, reference rays
runs=(
  "data/default_room/default_room.gltf 0.05 64 1 1024"
  "$work/furnished/furnished_room.gltf 0.05 64 1 1024"
  "$work/tile/open_world.gltf 0.5 16 1 64"
)
rows=()
results=()
for run in "${runs[@]}"; do
  read -r scene spacing rays bounces reference <<< "$run"
  json=$(build/bench/bench_adaptive "$scene" --spacing "$spacing" --rays "$rays" --bounces "$bounces" \
         --reference-rays "$reference" --points 4000 --out "$work/out" --json)
  results+=("$json")
  rows+=("$(python3 -c '
import json, sys
r = json.loads(sys.argv[1])
u, a = r["uniform"], r["adaptive"]
print("| {} | {} m | {} | {:,} | {:,} | **{:.2f}×** | {:,} | {:,} | **{:.2f}×** | {:.2f} % | {:.2f} % | **{:+.2f} %** | {:.2f} % | {:.1f} s / {:.1f} s |".format(
    r["scene"], r["spacing"], r["levels"], u["probes"], a["probes"], r["probe_ratio"], u["bytes"], a["bytes"],
    r["byte_ratio"], 100 * u["relative_rmse_against_reference"], 100 * a["relative_rmse_against_reference"],
    100 * r["rmse_added"], 100 * r["adaptive_against_uniform"], u["bake_seconds"], a["bake_seconds"]))
' "$json")")
done
plans=()
for spacing in 1 0.5; do
  plans+=("$(build/baker "$work/world/open_world.gltf" --placement adaptive --spacing "$spacing" --dry-run --json --quiet |
    python3 -c '
import json, sys
p = json.load(sys.stdin)["placement"]
placed = sum(l["probes"] for l in p["levels"])
print("| open_world.gltf (1 km) | {} m | {} | {:,} | {:,.0f} | **{:.2f}×** |".format(
    p["levels"][-1]["spacing"], " / ".join("{:,}".format(l["probes"]) for l in p["levels"]), placed,
    p["uniform_finest_probes"], p["uniform_finest_probes"] / placed))
')")
done

out=docs/adaptive/report.md
mkdir -p docs/adaptive
{
  echo "# Adaptive placement against a uniform grid"
  echo
  echo "Made by \`scripts/adaptive_report.sh\` with \`$(build/baker --version 2>&1 | head -n 1)\` on $(nproc) cores"
  echo "($(lscpu | sed -n 's/^Model name: *//p' | head -n 1)). Three levels, margin 1 cell. What each figure is:"
  echo "the comments at the top of \`bench/bench_adaptive.cpp\`; what they mean: [ADAPTIVE.md](../ADAPTIVE.md#measured)."
  echo "The open-world tile is \`make_open_world.py --size 200 --instances 240\` (the 1 km world's density)."
  echo
  echo "| scene | finest spacing | levels | uniform probes | adaptive probes | fewer probes | uniform bytes | adaptive bytes | fewer bytes | uniform RMSE | adaptive RMSE | added | adaptive vs uniform | bake uniform / adaptive |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|"
  printf '%s\n' "${rows[@]}"
  echo
  echo "RMSE: of E at 4 000 points a tenth of the spacing off the scene's surfaces, against a reference"
  echo "bake of the same uniform grid with more rays (16 times as many in the rooms, 4 times on the tile)"
  echo "and another seed, relative to its mean."
  echo
  echo "The whole 1 km open world, from the plan (\`--dry-run\`):"
  echo
  echo "| scene | finest spacing | probes per level (coarsest first) | adaptive probes | uniform probes | fewer probes |"
  echo "|---|---|---|---|---|---|"
  printf '%s\n' "${plans[@]}"
  echo
  echo "The JSON of each bench_adaptive run:"
  echo
  echo '```json'
  printf '%s\n' "${results[@]}"
  echo '```'
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
