#!/usr/bin/env bash
# Regenerates docs/sampling/quality_PRESET.md (and the index quality.md): what each `--quality`
# preset costs and how far it lands from Cycles. Per preset:
# scripts/reference_misses.py over the reference scenes (four seeds), then whole bakes of the
# bundled scenes, timed, with the rays their probes took.
#
#   scripts/quality_report.sh [PRESET ...]      (default: draft default final)
#   BAKE_SCENES="default_room sunlit_yard" scripts/quality_report.sh final
#
# BAKE_SCENES: which bundled scenes to bake whole (default: default_room sunlit_yard
# window_room). Needs build/baker and ../shared beside the checkout. Run it on a quiet machine:
# the seconds are wall time.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -d ../shared/data/reference ] || { echo "quality_report.sh: ../shared/data/reference is absent" >&2; exit 2; }
presets=("$@")
[ ${#presets[@]} -eq 0 ] && presets=(draft default final)
read -r -a scenes <<< "${BAKE_SCENES:-default_room sunlit_yard window_room}"
env=(--env ../shared/data/hdri/studio_small_03_1k.hdr)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
machine="$(nproc) cores ($(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ *//'))"
for q in "${presets[@]}"; do
  section="$tmp/quality_$q.md"
  {
    echo "## --quality $q"
    echo
    echo "Made by \`scripts/quality_report.sh $q\` with \`$(build/baker --version 2>&1 | head -n 1)\` on $machine."
    echo
    echo "Against Cycles, at the reference probes (\`scripts/reference_misses.py --seeds 1,2,3,4 -- --quality $q\`):"
    echo
  } > "$section"
  scripts/reference_misses.py --quiet --markdown "$tmp/misses.md" -- --quality "$q" > /dev/null || true
  { cat "$tmp/misses.md"; echo; } >> "$section"
  {
    echo "Whole bakes (\`baker SCENE --quality $q\`, default spacing, 3 reflections, sh-l2):"
    echo
    echo "| scene | probes traced | mean rays per probe | most rays | probes at the ray limit | bake seconds (trace and project) | rays traced in all |"
    echo "|---|---|---|---|---|---|---|"
  } >> "$section"
  for scene in "${scenes[@]}"; do
    args=()
    [ "$scene" != default_room ] && args=("${env[@]}")
    build/baker "data/$scene/$scene.gltf" --quality "$q" "${args[@]}" --json --quiet --out "$tmp/$scene.vdb" \
      > "$tmp/bake.json" 2> /dev/null
    python3 - "$scene" "$tmp/bake.json" >> "$section" <<'PY'
import json, sys
d = json.load(open(sys.argv[2]))
s = d["sampling"]
traced = d["probe_states"]["valid"] + d["probe_states"]["relocated"]
print("| %s | %d | %.0f | %d | %d | %.1f | %d |" % (sys.argv[1], traced, s["mean_rays_per_probe"],
      s["most_rays_per_probe"], s["probes_at_ray_limit"], d["seconds"]["trace_and_project"], d["rays_traced"]))
PY
  done
  mv "$section" "docs/sampling/quality_$q.md"
done
{
  echo "# Quality presets: error against Cycles, and cost"
  echo
  echo "One page per preset, each from \`scripts/quality_report.sh PRESET\`: how far a bake lands from"
  echo "Cycles at the reference probes over four seeds (a miss is a percentage of S = |E| + ½·(the"
  echo "probe's mean E); \"rays\" are lattice directions per probe, the mean over the scene's probes;"
  echo "the columns are those of [reference_misses.md](reference_misses.md)), and what whole bakes of"
  echo "the bundled scenes cost."
  echo
  for q in draft default final; do
    [ -f "docs/sampling/quality_$q.md" ] && echo "- [\`--quality $q\`](quality_$q.md)"
  done
} > "$tmp/quality.md"
mv "$tmp/quality.md" docs/sampling/quality.md
echo "wrote docs/sampling/quality.md"
