#!/usr/bin/env bash
# Regenerates docs/sampling/: how far `baker probe` lands from the Cycles references at several
# ray counts, over four independent seeds (scripts/reference_misses.py), one table per ray count.
#
#   scripts/sampling_report.sh [RAYS ...]      (default: 256 1024 4096 16384 65536)
#
# Needs build/baker and ../shared beside the checkout.
set -euo pipefail
cd "$(dirname "$0")/.."
[ -d ../shared/data/reference ] || { echo "sampling_report.sh: ../shared/data/reference is absent" >&2; exit 2; }
counts=("$@")
[ ${#counts[@]} -eq 0 ] && counts=(256 1024 4096 16384 65536)
mkdir -p docs/sampling
out=docs/sampling/reference_misses.md
{
  echo "# The baker against Cycles, by ray count"
  echo
  echo "Made by \`scripts/sampling_report.sh ${counts[*]}\` with \`$(build/baker --version 2>&1 | head -n 1)\`;"
  echo "each row is \`scripts/reference_misses.py --rays R --seeds 1,2,3,4\` (see its docstring for every column)."
  echo "A miss is a percentage of S = |E| + ½·(the probe's mean E); the tests' band is 2 % of S."
  echo
} > "$out.tmp"
for r in "${counts[@]}"; do
  scripts/reference_misses.py --rays "$r" --quiet --markdown "docs/sampling/rays_$r.md" > /dev/null || true
  { echo "## $r rays"; echo; cat "docs/sampling/rays_$r.md"; echo; } >> "$out.tmp"
  rm "docs/sampling/rays_$r.md"
done
mv "$out.tmp" "$out"
echo "wrote $out"
