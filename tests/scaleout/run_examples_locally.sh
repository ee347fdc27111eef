#!/usr/bin/env bash
# The scheduler templates of docs/examples/, run on this machine in the form they can take here:
# the Slurm array as N local processes with the variables Slurm sets, then its merge job; the
# Open Job Description template through tests/scaleout/run_openjd_locally.py. Each merged volume
# must be the one-process bake's bytes.
#   run_examples_locally.sh BAKER SOURCE_DIR WORK_DIR
set -euo pipefail
baker=$1 source=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
scene=$source/data/default_room/default_room.gltf
options="--spacing 0.3 --rays 16 --bounces 1 --basis ad-ycocg --quiet"
shards=3

# shellcheck disable=SC2086
"$baker" "$scene" $options --out whole.vdb

export BAKER=$baker SCENE=$scene PARTS=$work/slurm-parts OUT=$work/slurm.vdb BAKE_OPTIONS=$options
pids=()
for ((task = 0; task < shards; task++)); do
  SLURM_ARRAY_TASK_ID=$task SLURM_ARRAY_TASK_COUNT=$shards SLURM_CPUS_PER_TASK=1 \
    bash "$source/docs/examples/slurm_bake_shard.sbatch" & pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid"; done
bash "$source/docs/examples/slurm_merge.sbatch"
cmp whole.vdb slurm.vdb
echo "slurm array of $shards tasks + merge: the one-process bake's bytes"

python3 "$source/tests/scaleout/run_openjd_locally.py" "$source/docs/examples/openjd_bake.json" \
  "Baker=$baker" "SceneFile=$scene" "OutputVolume=$work/openjd.vdb" "PartsDirectory=$work/openjd-parts" \
  "Shards=$shards" "BakeOptions=$options"
cmp whole.vdb openjd.vdb
echo "open job description template, $shards tasks + merge: the one-process bake's bytes"
