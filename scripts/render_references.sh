#!/usr/bin/env bash
# Render the Blender Cycles reference panoramas used by scripts/check_reference.py.
#
#   scripts/render_references.sh [OUT_DIR] [SCENE ...]
#
# OUT_DIR defaults to build/reference (relative to the repository root). SCENE is any of
# cornell_box cornell_lights LightsPunctualLamp AlphaBlendModeTest (default: all four).
# For every scene and seed it writes OUT_DIR/<scene>/seed<N>/ with probe_*.exr, probes.json
# (reference_probe.py) and irradiance.json (panorama_sh.py --json: exact E(n) for n = ±X, ±Y, ±Z).
# check_reference.py averages the seed directories and reports their spread as the reference noise.
#
# Settings (environment variables override them):
#   RES=128x64 SPP=4096 SEEDS="0 1" (=> 8192 samples per pixel in the average)
#   BOUNCES=2  Cycles --bounces n allows n+1 diffuse reflections, so this matches `baker ... --bounces 3`
#   THREADS=1  keep a core free
# Needs Blender 3.4 (Debian: apt-get install blender python3-numpy) and ../shared beside the checkout.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"

OUT="${1:-build/reference}"
shift || true
SCENES=("$@")
[ ${#SCENES[@]} -eq 0 ] && SCENES=(cornell_box cornell_lights LightsPunctualLamp AlphaBlendModeTest)

RES="${RES:-128x64}"
SPP="${SPP:-4096}"
SEEDS="${SEEDS:-0 1}"
BOUNCES="${BOUNCES:-2}"
THREADS="${THREADS:-1}"

SHARED=../shared
TOOLS="$SHARED/tools"
DATA="$SHARED/data"
ENV_HDR="$DATA/hdri/potsdamer_platz_1k.hdr"   # used by AlphaBlendModeTest, strength 1, rotation 0

die() { echo "render_references.sh: $*" >&2; exit 2; }

# Blender's Debian build imports NumPy from the system Python: keep Debian's python3 first on PATH.
export PATH="/usr/bin:$PATH"

[ -d "$SHARED" ] || die "no $SHARED beside the checkout ($ROOT/..): the reference tools and scenes live there"
for f in "$TOOLS/reference_probe.py" "$TOOLS/panorama_sh.py" "$ENV_HDR"; do
  [ -f "$f" ] || die "missing $f"
done
command -v blender >/dev/null 2>&1 || die "blender not found (Debian: sudo apt-get install -y blender python3-numpy)"
blender -b --factory-startup --python-exit-code 3 --python-expr "import numpy" >/dev/null 2>&1 ||
  die "Blender's Python cannot import NumPy (Debian: sudo apt-get install -y python3-numpy; keep /usr/bin/python3 first on PATH)"

BLENDER=(blender -b --factory-startup --python-exit-code 3 --python)

# probe_hint positions of a scene as "--probe x,y,z" arguments
probe_hints() {
  python3 - "$1" <<'EOF'
import json, sys
hints = json.load(open(sys.argv[1]))["scenes"][0]["extras"]["probe_hint"]
print(" ".join("--probe %r,%r,%r" % tuple(p) for p in hints))
EOF
}

render() {  # render SCENE_NAME GLTF PROBE_ARGS... [-- EXTRA reference_probe ARGS]
  local name="$1" gltf="$2"; shift 2
  local seed dir
  for seed in $SEEDS; do
    dir="$OUT/$name/seed$seed"
    mkdir -p "$dir"
    echo "== $name seed $seed -> $dir" >&2
    "${BLENDER[@]}" "$TOOLS/reference_probe.py" -- "$gltf" "$@" \
      --res "$RES" --spp "$SPP" --bounces "$BOUNCES" --threads "$THREADS" --seed "$seed" \
      --out "$dir" >"$dir/render.log" 2>&1 || { tail -20 "$dir/render.log" >&2; die "reference_probe.py failed for $name (log: $dir/render.log)"; }
    grep '^\[reference_probe\]' "$dir/render.log" >&2 || true
    [ -f "$dir/probes.json" ] || die "no $dir/probes.json (log: $dir/render.log)"
    "${BLENDER[@]}" "$TOOLS/panorama_sh.py" -- "$dir" --json "$dir/irradiance.json" >"$dir/panorama_sh.log" 2>&1 ||
      { tail -20 "$dir/panorama_sh.log" >&2; die "panorama_sh.py failed for $dir"; }
    [ -f "$dir/irradiance.json" ] || die "no $dir/irradiance.json (log: $dir/panorama_sh.log)"
  done
}

for scene in "${SCENES[@]}"; do
  gltf="$DATA/scenes/$scene/$scene.gltf"
  [ -f "$gltf" ] || die "missing $gltf"
  case "$scene" in
    cornell_box|cornell_lights)
      # shellcheck disable=SC2046
      render "$scene" "$gltf" $(probe_hints "$gltf") ;;
    LightsPunctualLamp)
      # No probe hints: free space beside the lamp shade (+Z side, 0.30 m from the nearest surface)
      # and above/beside the lamp (0.38 m from the nearest surface). Black background.
      render "$scene" "$gltf" --probe 0.1,1.2,0.6 --probe 0.2,2.0,0.4 ;;
    AlphaBlendModeTest)
      # In front of the test planes (z = 0) above the base slab (top y = 0.1), and high above everything.
      render "$scene" "$gltf" --probe -0.75,1.0,0.5 --probe 1.5,0.6,0.35 --probe 0.0,2.8,0.3 \
        --env "$ENV_HDR" --env-strength 1 --env-rotation 0 ;;
    *) die "unknown scene $scene (known: cornell_box cornell_lights LightsPunctualLamp AlphaBlendModeTest)" ;;
  esac
done
echo "references in $OUT" >&2
