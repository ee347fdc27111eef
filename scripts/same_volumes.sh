#!/usr/bin/env bash
# Bakes one matrix of scenes × bases × settings with two baker binaries and compares the files
# byte for byte: what a refactoring must leave unchanged. Usage:
#   scripts/same_volumes.sh OLD_BAKER NEW_BAKER [WORKDIR]
# Scenes of ../shared/data are skipped (and said so) when it is absent. Exit 1 if any differ.
set -uo pipefail
cd "$(dirname "$0")/.."
old=$1 new=$2 work=${3:-$(mktemp -d)}
shared=../shared/data/scenes
bakes=(
  "room_sh.vdb|data/default_room/default_room.gltf --basis sh-l2 --rays 128 --spacing 0.5"
  "room_ycocg.vdb|data/default_room/default_room.gltf --basis ad-ycocg --rays 128 --spacing 0.5"
  "room_cube_nn.vdb|data/default_room/default_room.gltf --basis ambient-cube --non-negative --rays 128 --spacing 0.5"
  "room_sg.vdb|data/default_room/default_room.gltf --basis sg-12 --rays 128 --spacing 0.5 --seed 7"
  "room_draft.vdb|data/default_room/default_room.gltf --basis ad-srbf --quality draft --spacing 1.0"
  "room_adaptive.vdb|data/default_room/default_room.gltf --basis sh-l1 --placement adaptive --rays 64"
  "room_shard.vdb|data/default_room/default_room.gltf --basis sh-l2 --rays 64 --shard 1/3"
  "yard_rgb.vdb|data/sunlit_yard/sunlit_yard.gltf --basis ad-rgb --rays 128"
  "yard_sh3.vdb|data/sunlit_yard/sunlit_yard.gltf --basis sh-l3 --quality draft"
  "window_ycocg.vdb|data/window_room/window_room.gltf --basis ad-ycocg --rays 96 --spacing 0.6"
  "window_exr|data/window_room/window_room.gltf --basis sh-l2 --rays 96 --spacing 0.6 --format exr"
  "cornell_sg.vdb|$shared/cornell_box/cornell_box.gltf --basis sg-9 --rays 128 --window 3"
  "cornell_sh.vdb|$shared/cornell_box/cornell_box.gltf --basis sh-l2 --rays 128 --bounces 1 --no emission"
  "lamp_ycocg.vdb|$shared/LightsPunctualLamp/LightsPunctualLamp.gltf --basis ad-ycocg --rays 128"
  "fence_cube.vdb|$shared/alpha_fence/alpha_fence.gltf --basis ambient-cube --rays 128 --sky 0.5,0.6,0.9"
  "rooms_linear.vdb|$shared/two_rooms/two_rooms.gltf --basis ad-linear --rays 128 --threads 1"
)
same=0 differ=0
for entry in "${bakes[@]}"; do
  out=${entry%%|*} args=${entry#*|}
  scene=${args%% *}
  if [ ! -f "$scene" ]; then echo "skipped $out: $scene is absent"; continue; fi
  for side in old new; do
    mkdir -p "$work/$side"
    "${!side}" $args --quiet --out "$work/$side/$out" > /dev/null 2> "$work/$side/$out.log" ||
      { echo "$side baker failed on $out (see $work/$side/$out.log)"; exit 1; }
  done
  if diff -r "$work/old/$out" "$work/new/$out" > /dev/null; then
    echo "same     $out"; same=$((same + 1))
  else
    echo "DIFFERS  $out"; differ=$((differ + 1))
  fi
done
echo "$same the same, $differ different (files in $work)"
[ "$differ" -eq 0 ]
