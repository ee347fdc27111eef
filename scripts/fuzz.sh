#!/usr/bin/env bash
# Runs each libFuzzer target (fuzz/) for SECONDS (default 60) under AddressSanitizer and UBSan,
# from its seeds in tests/fuzz_corpus/TARGET/ (left as they are: new inputs go to
# build-sanitized/fuzz/corpus/TARGET/), with fuzz/TARGET.dict where there is one. Every target
# runs; the script fails if any found something. A finding's input is saved as
# build-sanitized/fuzz/TARGET-crash-… (or -leak-, -oom-, -timeout-), and
# build-sanitized/fuzz/fuzz_TARGET FILE reproduces it.
# Usage: scripts/fuzz.sh [SECONDS [TARGET ...]]   targets: gltf_loader vdb_reader exr_manifest engine_exports
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitized-build.sh
seconds=${1:-60}
if [ $# -gt 1 ]; then targets=("${@:2}"); else targets=(gltf_loader vdb_reader exr_manifest engine_exports); fi
build_sanitized "${targets[@]/#/fuzz_}"
# Whole allocation stacks, so that leak suppressions can name the library a leak is in: the
# fast unwinder stops at libstdc++, which keeps no frame pointers. Too slow for the test suite;
# the fuzzers meet those third-party leaks (corrupt PNG textures) at every turn.
export ASAN_OPTIONS="$ASAN_OPTIONS:fast_unwind_on_malloc=0"
failed=()
for target in "${targets[@]}"; do
  out="$sanitized_build/fuzz"
  mkdir -p "$out/corpus/$target"
  echo "fuzzing $target for $seconds s" >&2
  dictionary=()
  [ -f "fuzz/$target.dict" ] && dictionary=(-dict="fuzz/$target.dict")
  # 2 GiB and 10 s per input: beyond either is a finding (an unbounded allocation, a hang).
  if "$out/fuzz_$target" "$out/corpus/$target" "tests/fuzz_corpus/$target" "${dictionary[@]}" \
      -max_total_time="$seconds" -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 \
      -artifact_prefix="$out/$target-" -print_final_stats=1 > "$out/$target.log" 2>&1; then
    grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb" "$out/$target.log" >&2 || true
  else
    tail -n 60 "$out/$target.log" >&2
    echo "fuzz_$target found a problem (whole log: $out/$target.log)" >&2
    failed+=("$target")
  fi
done
# Every target runs, so that one run reports every target's finding.
if [ ${#failed[@]} -gt 0 ]; then
  echo "fuzzing found problems in: ${failed[*]}" >&2
  exit 1
fi
