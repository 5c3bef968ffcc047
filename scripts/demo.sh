#!/usr/bin/env bash
# The default job behind `make demo`: see README.md.
set -euo pipefail
quadtri=$1
out=$2
mkdir -p "$out"
"$quadtri" mesh icosahedron -o "$out/icosahedron.obj"
