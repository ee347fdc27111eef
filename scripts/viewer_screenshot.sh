#!/usr/bin/env bash
# The screenshot README shows: the page `baker view` writes for the bundled room (ad-ycocg), taken
# by the viewer's test in headless Chromium, into docs/images/viewer_default_room.png.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build -j2 --target baker baker_viewer_bundle
node tests/engines/viewer.test.mjs build/baker . docs/images/viewer_default_room.png
