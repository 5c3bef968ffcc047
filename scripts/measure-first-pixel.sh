#!/usr/bin/env bash
# Time to first pixel and peak resident memory of `quadtri render` on a large mesh, per model,
# beside `shading`'s: a 1,000,000-triangle torus (`quadtri mesh torus --segments 1000 --rings
# 500`) under a constant sky and a point light, 32x32 pixels at 1 sample per pixel, so the
# render is dominated by what comes before it: loading, conversion and the acceleration
# structure. Each model runs in its own process, one after the other; the times are the
# command's own summary lines (`scene build`, `first pixel`, `peak memory`).
#
# Usage: scripts/measure-first-pixel.sh [MODELS] [SEGMENTS RINGS]
#   MODELS    comma-separated (default: every model of `quadtri convert --help`)
#   SEGMENTS RINGS   the torus' divisions (default 1000 500: 2·S·R = 1,000,000 triangles)
# Environment: QUADTRI (default build/src/cli/quadtri), THREADS (default: all cores), REPEAT
# (default 3: each model takes turns with shading that many times, each keeping its fastest).
# Prints a Markdown table; the ratios are each model's figure over shading's, each marked
# "pass" or "MISSED" against its target (first pixel within 1.5x, peak within 2x).
set -euo pipefail
cd "$(dirname "$0")/.."
quadtri=${QUADTRI:-build/src/cli/quadtri}
[ -x "$quadtri" ] || { echo "$quadtri is not built (cmake --build build --target quadtri)" >&2; exit 1; }
models=${1:-}
segments=${2:-1000}
rings=${3:-500}
threads=${THREADS:-0}
if [ -z "$models" ]; then
  models=$("$quadtri" convert --help | sed -n 's/.*--model TEXT:{\([^}]*\)}.*/\1/p')
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$quadtri" mesh torus --segments "$segments" --rings "$rings" -o "$work/torus.ply" >/dev/null
cat >"$work/scene.xml" <<XML
<scene version="3.0.0">
  <default name="model" value="shading"/>
  <integrator type="path"><integer name="max_depth" value="4"/></integrator>
  <sensor type="perspective">
    <float name="fov" value="40"/>
    <transform name="to_world"><lookat origin="0, 2.2, 2.2" target="0, 0, 0" up="0, 1, 0"/></transform>
    <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/></film>
    <sampler type="independent"><integer name="sample_count" value="1"/></sampler>
  </sensor>
  <shape type="ply">
    <string name="filename" value="torus.ply"/>
    <string name="model" value="\$model"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.8, 0.8, 0.8"/></bsdf>
  </shape>
  <emitter type="constant"><rgb name="radiance" value="0.4, 0.45, 0.5"/></emitter>
  <emitter type="point"><point name="position" value="2, 3, 3"/><rgb name="intensity" value="12, 12, 12"/></emitter>
</scene>
XML
triangles=$((2 * segments * rings))
echo "Time to first pixel and peak memory, $triangles-triangle torus, 32x32 at 1 spp ($(nproc) cores, threads=$threads)"
echo
echo "| model | scene build (s) | first pixel (s) | shading's (s) | ÷ shading (target ≤ 1.5) | peak memory (MiB) | shading's (MiB) | ÷ shading (target ≤ 2) |"
echo "|---|---:|---:|---:|---:|---:|---:|---:|"
repeat=${REPEAT:-3}
# One render's summary lines: "BUILD FIRST PEAK", or the error's last line.
run_one() {
  local out
  out=$("$quadtri" render "$work/scene.xml" --model "$1" --threads "$threads" -o "$work/$1.exr" 2>&1) || {
    echo "failed: $(echo "$out" | tail -1)"
    return
  }
  echo "$(echo "$out" | sed -n 's/^scene build *\([0-9.]*\) s.*/\1/p')" \
    "$(echo "$out" | sed -n 's/^first pixel *\([0-9.]*\) s.*/\1/p')" \
    "$(echo "$out" | sed -n 's/^peak memory *\([0-9.]*\) MiB.*/\1/p')"
}
min() { awk -v a="$1" -v b="$2" 'BEGIN { print (b == "" || a + 0 < b + 0) ? a : b }'; }
# The ratio a / b, then "pass", or "MISSED" where it is above the target c.
against() { awk -v a="$1" -v b="$2" -v c="$3" 'BEGIN { printf "%.2f%s", a / b, (a / b > c ? " MISSED" : " pass") }'; }
# Each model takes turns with shading, REPEAT times; each keeps its fastest run (the machine's
# load only ever adds time) and its ratios are to shading's fastest run among those turns.
for model in ${models//,/ }; do
  [ "$model" = shading ] && continue
  sf="" sp="" mb="" mf="" mp="" failed=""
  for ((r = 0; r < repeat; ++r)); do
    read -r b f p <<<"$(run_one shading)"
    sf=$(min "$f" "$sf") sp=$(min "$p" "$sp")
    result=$(run_one "$model")
    if [[ $result == failed:* ]]; then failed=$result; break; fi
    read -r b f p <<<"$result"
    mb=$(min "$b" "$mb") mf=$(min "$f" "$mf") mp=$(min "$p" "$mp")
  done
  if [ -n "$failed" ]; then
    echo "| $model | $failed | | | | | | |"
    continue
  fi
  echo "| $model | $mb | $mf | $sf | $(against "$mf" "$sf" 1.5) | $mp | $sp | $(against "$mp" "$sp" 2) |"
done
