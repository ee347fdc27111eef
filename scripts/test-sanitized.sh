#!/usr/bin/env bash
# The whole test suite under AddressSanitizer (with LeakSanitizer) and UBSan, built with clang
# into build-sanitized/; non-zero when a test fails or a sanitizer reports anything.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitized-build.sh
build_sanitized baker baker_tests importer_check decoder_samples baker_viewer_bundle
ctest --test-dir "$sanitized_build" --output-on-failure -j2 --timeout 900
