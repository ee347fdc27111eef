#!/usr/bin/env bash
# Regenerates docs/ACCURACY.md's "What accuracy costs": `baker accuracy` on the bundled scene and on one
# Khronos sample scene (from ../shared/data, when present), writing docs/accuracy/<scene>/
# (CSV, JSON, SVG plot, Markdown table). Run from the repository root after a build.
set -euo pipefail
cd "$(dirname "$0")/.."
baker=build/baker
[ -x "$baker" ] || { echo "build first: $baker is missing (scripts/setup.sh)" >&2; exit 2; }
bases=sh-l2,sg-12,ad-srbf,ad-rgb,ad-ycocg
rays=64,256,1024,4096
"$baker" accuracy data/default_room/default_room.gltf --basis "$bases" --rays "$rays" --bounces 3 \
  --reference-rays 65536 --out docs/accuracy/default_room
khronos=../shared/data/scenes/LightsPunctualLamp/LightsPunctualLamp.gltf
if [ -f "$khronos" ]; then
  "$baker" accuracy "$khronos" --basis "$bases" --rays "$rays" --bounces 3 --reference-rays 65536 \
    --out docs/accuracy/LightsPunctualLamp
else
  echo "../shared/data is not beside this checkout: skipping the Khronos scene" >&2
fi
