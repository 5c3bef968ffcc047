#!/usr/bin/env bash
# Reproduces the thesis' chapter 5 results (docs/DESIGN.md §6): fetches the Utah teapot once and
# runs `quadtri reproduce`, which renders and measures everything, writes docs/RESULTS.md,
# docs/images/*.png and docs/results/*.csv, and exits 1 when a speed or memory target is missed.
#
# Usage: scripts/reproduce.sh [--quick|--full] [more `quadtri reproduce` options]
# Needs a built quadtri (QUADTRI=path/to/quadtri, default build/src/cli/quadtri), and node/npm
# once for the teapot (scripts/fetch-teapot.sh writes data/teapot.obj).
set -euo pipefail
cd "$(dirname "$0")/.."
quadtri=${QUADTRI:-build/src/cli/quadtri}
[ -x "$quadtri" ] || { echo "$quadtri is not built (cmake --build build --target quadtri)" >&2; exit 1; }
scripts/fetch-teapot.sh data/teapot.obj
exec "$quadtri" reproduce --commit "$(git rev-parse --short HEAD 2>/dev/null || echo unknown)" "$@"
