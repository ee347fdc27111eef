#!/usr/bin/env bash
# Bakes SCENE in N shards as a Slurm job array, then merges them into OUT:
#   docs/examples/slurm_submit.sh SCENE N OUT [BAKE OPTIONS...]
# e.g. slurm_submit.sh level.gltf 64 level.vdb --spacing 0.5 --basis ad-ycocg
# The parts go to OUT's name with .parts; the merged volume is byte for byte the one a single
# machine would write with the same options.
set -euo pipefail
if [ $# -lt 3 ]; then
  echo "usage: $0 SCENE N OUT [BAKE OPTIONS...]" >&2
  exit 2
fi
scene=$1 shards=$2 out=$3
shift 3
here=$(cd "$(dirname "$0")" && pwd)
export SCENE=$scene PARTS=$out.parts OUT=$out BAKE_OPTIONS="$*"
array=$(sbatch --parsable --export=ALL --array="0-$((shards - 1))" "$here/slurm_bake_shard.sbatch")
sbatch --parsable --export=ALL --dependency="afterok:${array%%;*}" "$here/slurm_merge.sbatch"
