#!/usr/bin/env bash
# Re-renders the pictures of the quadric-g1 model (G1_PICTURES_SNIPPET.md), so that they can be
# made again once the model is ray traced directly instead of through its tessellation.
#
# Usage: scripts/render-g1-figures.sh BIN OUTDIR
#   BIN     the quadtri binary (e.g. build/quadtri)
#   OUTDIR  folder for the PNGs and the render-time CSVs (created if missing); pass docs/images
#           to replace the committed images (the CSVs then land there too: move them to
#           docs/results)
# Environment:
#   CORPUS  the real-mesh corpus (scripts/fetch-corpus.sh); default ./corpus. Needs cgal/*.off
#           and npm/teapot.obj.
#   TEAPOT  the teapot of the thesis scenes; default data/teapot.obj, else $CORPUS/npm/teapot.obj
#           (the same npm package, see scripts/fetch-teapot.sh).
# Run it from the repository root. On 2 shared cores the whole set takes a few minutes.
set -euo pipefail

if [[ $# -ne 2 ]]; then
  echo "usage: $0 BIN OUTDIR" >&2
  exit 2
fi
bin=$1
out=$2
corpus=$(realpath "${CORPUS:-corpus}")
teapot=${TEAPOT:-data/teapot.obj}
[[ -f $teapot ]] || teapot=$corpus/npm/teapot.obj
teapot=$(realpath "$teapot")
mkdir -p "$out"

for f in "$corpus/cgal/cow.off" "$corpus/npm/teapot.obj" "$teapot"; do
  [[ -f $f ]] || { echo "$0: missing $f (run scripts/fetch-corpus.sh)" >&2; exit 1; }
done

all_models=flat,shading,shading-offset,quadric-edges,quadric-param,quadric-implicit
all_models+=,quadric-edges-eq42,quadric-implicit-robust,phong,pn,nagata,quadric-g1

# 1. Close-ups (scenes/g1/closeup-*.xml): the 80-triangle icosphere and the cow, framed so that a
#    silhouette and the terminator of a grazing point light both fill the frame. `shading` has a
#    polygonal silhouette and a faceted terminator, `shading-offset` smooths the terminator but
#    keeps the polygonal silhouette, `pn` and `quadric-g1` have neither.
"$bin" figure --setup closeup --shapes icosphere,cow \
  --models shading,shading-offset,pn,quadric-g1 --scenes scenes/g1 -D corpus="$corpus" \
  --res 256 --spp 64 -o "$out/g1_closeups.png" --csv "$out/g1_closeups_times.csv"

# 2. Reflection lines (scenes/g1/reflect-*.xml): a perfect mirror in a ring of tilted emissive
#    bars. Where the surface or its shading normal is only C0, the reflected bars kink at the
#    edges; on a G1 surface they stay continuous. The zooms (right of the icosphere's centre, the
#    front of the teapot's body) show the lines at a size where kinks and jogs can be told apart.
"$bin" figure --setup reflect --shapes icosphere,teapot \
  --models shading,quadric-param,pn,quadric-g1 --scenes scenes/g1 -D corpus="$corpus" \
  --res 256 --spp 32 -o "$out/g1_reflection_lines.png" --csv "$out/g1_reflection_lines_times.csv"
"$bin" figure --setup reflect --shapes icosphere-zoom,teapot-zoom \
  --models shading,quadric-param,pn,quadric-g1 --scenes scenes/g1 -D corpus="$corpus" \
  --res 256 --spp 32 -o "$out/g1_reflection_zoom.png" --csv "$out/g1_reflection_zoom_times.csv"

# 3. The real-meshes grid of docs/REAL_MESHES.md (scenes/corpus/grid-*.xml) with a quadric-g1
#    column: folds show as black patches (nagata, quadric-param), cracks as slits.
"$bin" figure --setup grid --shapes cow,elephant,fandisk,armadillo,pinion \
  --models shading,shading-offset,quadric-param,quadric-implicit-robust,pn,nagata,quadric-g1 \
  --scenes scenes/corpus -D corpus="$corpus" --spp 32 --res 200 \
  -o "$out/real_meshes.png" --csv "$out/real_meshes_times.csv"

# 4. Every model on the teapot and the torus, in the thesis' setups (scenes/thesis): (a) diffuse
#    in a room under a point light, (b) glass. The settings are `quadtri reproduce`'s quick ones
#    (src/report/reproduce.cpp, everyA/everyB): (a) 160 px at 32 spp, (b) 128 px with the
#    scenes' adaptive sampler capped at 64 spp.
"$bin" figure --setup a --shapes teapot,torus --models "$all_models" --scenes scenes/thesis \
  -D teapot="$teapot" --res 160 --spp 32 -o "$out/models_a.png" --csv "$out/models_times_a.csv"
"$bin" figure --setup b --shapes teapot,torus --models "$all_models" --scenes scenes/thesis \
  -D teapot="$teapot" --res 128 -D spp=64 -o "$out/models_b.png" --csv "$out/models_times_b.csv"
