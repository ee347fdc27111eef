#!/usr/bin/env bash
# Runs each libFuzzer target (fuzz/) for SECONDS (default 60) under AddressSanitizer and UBSan,
# starting from its seeds in tests/fuzz_corpus/TARGET/ (left as they are: new inputs go to
# build-sanitized/fuzz/corpus/TARGET/). Non-zero on the first finding; the input is saved as
# build-sanitized/fuzz/TARGET-crash-… (or -leak-, -oom-, -timeout-): reproduce it with
# build-sanitized/fuzz/fuzz_TARGET FILE.
# Usage: scripts/fuzz.sh [SECONDS [TARGET ...]]   targets: gltf_loader vdb_reader exr_manifest
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/sanitized-build.sh
seconds=${1:-60}
if [ $# -gt 1 ]; then targets=("${@:2}"); else targets=(gltf_loader vdb_reader exr_manifest); fi
build_sanitized "${targets[@]/#/fuzz_}"
for target in "${targets[@]}"; do
  out="$sanitized_build/fuzz"
  mkdir -p "$out/corpus/$target"
  echo "fuzzing $target for $seconds s" >&2
  # 2 GiB and 10 s per input: beyond either is a finding (an unbounded allocation, a hang).
  if ! "$out/fuzz_$target" "$out/corpus/$target" "tests/fuzz_corpus/$target" -max_total_time="$seconds" \
      -rss_limit_mb=2048 -malloc_limit_mb=2048 -timeout=10 -artifact_prefix="$out/$target-" \
      -print_final_stats=1 > "$out/$target.log" 2>&1; then
    cat "$out/$target.log" >&2
    echo "fuzz_$target found a problem; its log: $out/$target.log" >&2
    exit 1
  fi
  grep -E "^stat::number_of_executed_units|^stat::peak_rss_mb|^#[0-9]+.*DONE" "$out/$target.log" >&2 || true
done
