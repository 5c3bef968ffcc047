#!/usr/bin/env bash
# The default job behind `make demo` (see README.md): renders the default scene, and analyses a
# built-in icosahedron under every model with its heatmaps.
set -euo pipefail
quadtri=$1
out=$2
mkdir -p "$out"
"$quadtri" render scenes/default.xml -o "$out/default.exr" -o "$out/default.png"
"$quadtri" analyze icosahedron --model all --heatmaps "$out/heatmaps" > "$out/analysis.txt"
cat "$out/analysis.txt"
echo "wrote $out/default.png, $out/default.exr, $out/analysis.txt and $out/heatmaps/"
