#!/usr/bin/env bash
# Renders one image as a Slurm job array: task I of N renders `quadtri render --tile I/N`, and
# the first task submits a merge job that runs once every task has succeeded.
#
#   sbatch --array=1-16 scripts/slurm-render.sh SCENE.xml OUT.exr [render options...]
#
# The tiles go to OUT.tiles/tile-I.exr, the merged image to OUT.exr. The array must be
# contiguous (1-N, or any A-B: tile I is task A+I-1). QUADTRI names the binary (default:
# quadtri on PATH). Edit the #SBATCH lines to fit the cluster.
#SBATCH --job-name=quadtri-render
#SBATCH --cpus-per-task=8
#SBATCH --time=02:00:00
#SBATCH --output=slurm-%A_%a.out
set -euo pipefail
if [ $# -lt 2 ] || [ -z "${SLURM_ARRAY_TASK_ID:-}" ]; then
  echo "usage: sbatch --array=1-N $0 SCENE.xml OUT.exr [render options...]" >&2
  exit 2
fi
quadtri=${QUADTRI:-quadtri}
scene=$1
out=$2
shift 2
tiles="${out%.exr}.tiles"
count=${SLURM_ARRAY_TASK_COUNT}
index=$((SLURM_ARRAY_TASK_ID - SLURM_ARRAY_TASK_MIN + 1))
mkdir -p "$tiles"

if [ "$SLURM_ARRAY_TASK_ID" -eq "$SLURM_ARRAY_TASK_MIN" ]; then
  # Every tile by name, so that merge names a missing one; afterok: the merge runs only if
  # every task of the array exited 0.
  merge=("$quadtri" merge)
  for i in $(seq "$count"); do merge+=("${tiles}/tile-${i}.exr"); done
  merge+=(-o "$out")
  sbatch --dependency="afterok:${SLURM_ARRAY_JOB_ID}" --job-name=quadtri-merge \
    --output="slurm-${SLURM_ARRAY_JOB_ID}-merge.out" --wrap "$(printf '%q ' "${merge[@]}")" ||
    echo "warning: submitting the merge failed; run: ${merge[*]}" >&2
fi

# srun forwards SIGTERM at the time limit: the tile is written with the pixels done so far.
exec srun "$quadtri" render "$scene" --threads "${SLURM_CPUS_PER_TASK:-0}" \
  --tile "${index}/${count}" -o "${tiles}/tile-${index}.exr" "$@"
