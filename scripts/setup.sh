#!/usr/bin/env bash
# Quick start, step 1: install what is missing, build into build/, bake the default scene.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build -j2
build/baker data/default_room/default_room.gltf --basis sh-l2 --out build/default_room.vdb
