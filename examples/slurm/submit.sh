#!/bin/bash

# SPDX-FileCopyrightText: The Strata authors
# SPDX-License-Identifier: MIT

# Submits a Strata world bake to Slurm: a job array of workers (at most
# THROTTLE at a time) and a finalize job that runs when all of them
# succeeded. Prints the two job ids.
#   examples/slurm/submit.sh SCENE DIR [TILES_PER_WORKER] [THROTTLE] [-- BAKE FLAGS...]
# e.g. submit.sh world.toml /shared/world 4 16 -- --tile-size 256 --lods 4
# STRATA names the strata executable (default: strata on PATH); the output
# folder must be on storage every node sees.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
scene=$(realpath "$1") dir=$(realpath -m "$2") per_worker=${3:-1} throttle=${4:-8}
shift $(($# < 4 ? $# : 4))
[[ ${1:-} == -- ]] && shift
extra=("$@")
strata=${STRATA:-strata}
# The array and the memory per task come from the plan (one sample tile).
plan=$("$strata" bake "$scene" --plan --tiles-per-worker "$per_worker" "${extra[@]}")
array=$(sed -n 's/^  array *//p' <<<"$plan")
mem=$(sed -n 's/.*--mem=\([0-9]*M\).*/\1/p' <<<"$plan")
mkdir -p "$dir"
# Slurm's logs (strata-bake-JOB_TASK.out) go to the folder you submit from.
# STRATA reaches the tasks through the submitting environment (sbatch's
# default --export=ALL): with "--export=ALL,STRATA=..." Slurm 22.05 loaded
# the user's login environment on the node before each task (su -), which
# costs seconds and can hang on a slow profile.
export STRATA="$strata"
bake_job=$(sbatch --parsable --array="$array%$throttle" --mem="$mem" \
  "$here/bake.sbatch" "$scene" "$dir" "$per_worker" "${extra[@]}")
final_job=$(sbatch --parsable --dependency=afterok:"$bake_job" "$here/finalize.sbatch" "$dir")
echo "$bake_job $final_job"
