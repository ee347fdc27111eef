#!/usr/bin/env bash
# Regenerates docs/scaling/bench_scaleout.md: bench/bench_scaleout.sh --large on this machine
# (about 15 minutes on 2 cores), its JSON as printed.
#
#   scripts/scaling_report.sh
#
# Needs build/baker built with Open MPI.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p docs/scaling
out=docs/scaling/bench_scaleout.md
json=$(bench/bench_scaleout.sh build --large)
{
  echo "# Scale-out benchmark"
  echo
  echo "Made by \`scripts/scaling_report.sh\` (\`bench/bench_scaleout.sh build --large\`) with"
  echo "\`$(build/baker --version 2>&1 | head -n 1)\` on $(nproc) cores ($(lscpu | sed -n 's/^Model name: *//p' | head -n 1))."
  echo "What each figure is: the comments at the top of bench/bench_scaleout.sh; what they mean: [SCALING.md](../SCALING.md#what-it-costs)."
  echo
  echo '```json'
  echo "$json"
  echo '```'
} > "$out.tmp"
mv "$out.tmp" "$out"
echo "wrote $out"
