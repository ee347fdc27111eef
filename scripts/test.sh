#!/usr/bin/env bash
# Quick start, step 2: build (if needed) and run the whole test suite; non-zero if any test fails.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/install-deps.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=RelWithDebInfo > /dev/null
cmake --build build -j2
ctest --test-dir build --output-on-failure -j2
