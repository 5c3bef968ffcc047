#!/usr/bin/env bash
# The randomized soak without a bound (README "Reliability"): runs quadtri_soak on seed SEED,
# SEED+1, … (default from 1), 500 cases each, until stopped or until a case fails, which prints
# the seed and case that reproduce it. Corpus meshes join when QUADTRI_CORPUS names the corpus
# folder (scripts/fetch-corpus.sh), or ./corpus when it exists.
#
#   scripts/soak.sh [SEED] [BUILD]        BUILD: the build folder (default build)
set -euo pipefail
cd "$(dirname "$0")/.."
seed=${1:-1}
build=${2:-build}
soak="$build/tests/quadtri_soak"
[ -x "$soak" ] || { echo "soak.sh: $soak is not built (make build)" >&2; exit 2; }
corpus=${QUADTRI_CORPUS:-}
if [ -z "$corpus" ] && [ -d corpus ]; then corpus=corpus; fi
args=()
if [ -n "$corpus" ]; then args=(--corpus "$corpus"); fi
while true; do
  "$soak" --seed "$seed" --count 500 "${args[@]}"
  seed=$((seed + 1))
done
