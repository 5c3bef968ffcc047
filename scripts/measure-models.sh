#!/usr/bin/env bash
# Measures every model (docs/DESIGN.md §4): fetches the Utah teapot once and runs
# `quadtri reproduce --models-only`, which writes docs/results/models_*.csv,
# docs/images/convergence.png and the Markdown fragment docs/results/models.md.
#
# Usage: scripts/measure-models.sh [--lines N] [--levels L]
# Needs a built quadtri (QUADTRI=path/to/quadtri, default build/src/cli/quadtri), and node/npm
# once for the teapot (scripts/fetch-teapot.sh writes data/teapot.obj).
set -euo pipefail
cd "$(dirname "$0")/.."
quadtri=${QUADTRI:-build/src/cli/quadtri}
[ -x "$quadtri" ] || { echo "$quadtri is not built (cmake --build build --target quadtri)" >&2; exit 1; }
scripts/fetch-teapot.sh data/teapot.obj
exec "$quadtri" reproduce --models-only \
  --commit "$(git rev-parse --short HEAD 2>/dev/null || echo unknown)" "$@"
