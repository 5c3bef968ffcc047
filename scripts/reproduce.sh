#!/usr/bin/env bash
# Reproduces the thesis' chapter 5 results (docs/DESIGN.md §6) and writes docs/RESULTS.md,
# docs/images/*.png and docs/results/*.csv.
#
# Usage: scripts/reproduce.sh [--quick|--full]
#   --quick (default): 96x96 images, 32 spp in setup (a); 88x88, adaptive up to 64 spp in (b),
#                      each cell rendered 3 times; icospheres of levels 0..7 (20 .. 327,680
#                      patches) at 128x128, 16 spp, each cell rendered 5 times. About 4 minutes
#                      on 2 cores.
#   --full:            the scenes' own settings: 256x256, 64 spp (a), adaptive up to 500 spp (b),
#                      each cell rendered 3 times, icospheres of levels 0..7 at 128x128, 16 spp,
#                      5 times, and the teapot in table 5.1 too. Hours on 2 cores.
# Render times: `quadtri figure --repeat N` builds a shape's models together and renders them in
# N rounds, rotating the models' order each round; the tables give the median over rounds of the
# side-by-side ratio and, in brackets, its range over the rounds.
# Needs a built quadtri (QUADTRI=path/to/quadtri, default build/src/cli/quadtri), and node/npm
# once for the Utah teapot (scripts/fetch-teapot.sh writes data/teapot.obj). Intermediate files
# go to out/reproduce/. Only bash, awk and quadtri itself are used.
set -euo pipefail
cd "$(dirname "$0")/.."

mode=quick
case "${1:---quick}" in
  --quick) mode=quick ;;
  --full) mode=full ;;
  *) echo "usage: $0 [--quick|--full]" >&2; exit 2 ;;
esac
quadtri=${QUADTRI:-build/src/cli/quadtri}
[ -x "$quadtri" ] || { echo "$quadtri is not built (cmake --build build --target quadtri)" >&2; exit 1; }

shapes=triangle,tetrahedron,icosahedron,teapot
models=shading,quadric-edges,quadric-param,quadric-implicit
if [ "$mode" = quick ]; then
  grid_a=(--res 96 --spp 32 --repeat 3); grid_b=(--res 88 -D spp=64 --repeat 3)
  every_a=(--res 160 --spp 32); every_b=(--res 128 -D spp=64)
  levels=7; scaling=(--res 128 --spp 16 --repeat 5); table_shapes="triangle tetrahedron icosahedron"
else
  grid_a=(--repeat 3); grid_b=(--repeat 3); levels=7; scaling=(--repeat 5)
  every_a=(); every_b=()
  table_shapes="triangle tetrahedron icosahedron data/teapot.obj"
fi

work=out/reproduce
mkdir -p "$work" docs/images docs/results data
scripts/fetch-teapot.sh data/teapot.obj
for ((l = 0; l <= levels; l++)); do
  [ -s "data/icosphere-$l.obj" ] || "$quadtri" mesh icosphere --level "$l" -o "data/icosphere-$l.obj" >/dev/null
done

# Figures 5.1 and 5.2 with the render times of tables 5.2 and 5.3.
"$quadtri" figure --setup a --shapes "$shapes" --models "$models" "${grid_a[@]}" \
  -o docs/images/fig5_1_diffuse.png --csv docs/results/times_a.csv
"$quadtri" figure --setup b --shapes "$shapes" --models "$models" "${grid_b[@]}" \
  -o docs/images/fig5_2_glass.png --csv docs/results/times_b.csv
# Figure 5.5 extended: icospheres of growing level; the last model is the ratios' numerator.
icospheres=$(seq -s, -f 'icosphere-%g' 0 "$levels")
"$quadtri" figure --setup scaling --shapes "$icospheres" \
  --models shading,quadric-param,quadric-implicit "${scaling[@]}" \
  -o "$work/scaling_grid.png" --csv docs/results/times_scaling.csv \
  --ratio-plot docs/images/fig5_5_ratio.png
# Figures 5.3 and 5.4 (corners-only and 2500-point tessellations of the parametric models),
# 5.6 and 6.2 (the implicit model's heatmaps on the icosahedron and the teapot).
for s in tetrahedron icosahedron; do
  "$quadtri" analyze "$s" --heatmaps "$work/views-$s" >/dev/null 2>&1
  for m in quadric-edges quadric-param; do
    for k in corners 2500; do cp "$work/views-$s/$m-view-$k.png" "docs/images/fig5_3_4_$s-$m-$k.png"; done
  done
done
# Table 5.1 (thesis tessellation: 4802 triangles per patch) and the constraint metrics.
echo "model,mesh,triangles,primitives,memory_bytes,convert_seconds,vertex_position_error,vertex_normal_error_deg,vertex_normal_flip_rate,c0_gap,c1_angle_deg,crack_rate,truth_distance" \
  > docs/results/primitives.csv
for s in $table_shapes; do
  normals=file  # the built-in shapes' sphere normals; the teapot has none: thesis eq. 2.8
  [ "$s" = data/teapot.obj ] && normals=average
  "$quadtri" analyze "$s" --normals "$normals" --tessellation thesis --lines 200 --csv |
    tail -n +2 >> docs/results/primitives.csv
done
"$quadtri" analyze icosahedron --csv --heatmaps "$work/heat-icosahedron" --heatmap-width 800 \
  > docs/results/icosahedron_metrics.csv 2>/dev/null
"$quadtri" analyze data/teapot.obj --normals average --csv --model quadric-implicit \
  --heatmaps "$work/heat-teapot" --heatmap-width 640 > /dev/null 2>&1
"$quadtri" analyze data/teapot.obj --normals average --csv > docs/results/teapot_metrics.csv
for f in residual normal-misfit; do
  cp "$work/heat-icosahedron/quadric-implicit-$f.png" "docs/images/fig5_6_icosahedron-$f.png"
  cp "$work/heat-teapot/quadric-implicit-$f.png" "docs/images/fig6_2_teapot-$f.png"
done
[ -x scripts/measure-models.sh ] && scripts/measure-models.sh
# Issue 5: the teapot and the torus under every model, baselines included, setups (a) and (b).
every_model=flat,shading,shading-offset,quadric-edges,quadric-param,quadric-implicit,quadric-edges-eq42,quadric-implicit-robust,phong,pn,nagata
"$quadtri" figure --setup a --shapes teapot,torus --models "$every_model" ${every_a[@]+"${every_a[@]}"} \
  -o docs/images/models_a.png --csv docs/results/models_times_a.csv
"$quadtri" figure --setup b --shapes teapot,torus --models "$every_model" ${every_b[@]+"${every_b[@]}"} \
  -o docs/images/models_b.png --csv docs/results/models_times_b.csv

# Markdown helpers over the CSVs (awk, no other tools).
pivot() {  # CSV, value column, scale, format -> rows = models, columns = shapes
  awk -F, -v col="$2" -v scale="$3" -v fmt="$4" -v models="$models" -v shapes="$shapes" '
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { v[$(idx["model"]) "," $(idx["shape"])] = $(idx[col]) }
    END {
      ns = split(shapes, s, ","); nm = split(models, m, ",")
      printf "| model |"; for (j = 1; j <= ns; j++) printf " %s |", s[j]; printf "\n|---|"
      for (j = 1; j <= ns; j++) printf "---:|"; printf "\n"
      for (i = 1; i <= nm; i++) {
        printf "| %s |", m[i]
        for (j = 1; j <= ns; j++) {
          k = m[i] "," s[j]
          if (k in v) printf " " fmt " |", v[k] * scale; else printf " - |"
        }
        printf "\n"
      }
    }' "$1"
}
# awk: ratio(NUM, DEN) of two ';'-separated lists of per-round times is the median of the
# per-round ratios, and sets LO and HI to their range (the ratio of the medians without rounds).
ratio_awk='
  function ratio(num, den,   a, b, n, r, i, j, t, k) {
    n = split(num, a, ";")
    if (n != split(den, b, ";")) { n = 1; a[1] = median(num); b[1] = median(den) }
    for (i = 1; i <= n; i++) r[i] = b[i] > 0 ? a[i] / b[i] : 0
    for (i = 2; i <= n; i++) for (j = i; j > 1 && r[j - 1] > r[j]; j--) { t = r[j]; r[j] = r[j - 1]; r[j - 1] = t }
    LO = r[1]; HI = r[n]; k = int((n + 1) / 2)
    return n % 2 ? r[k] : (r[k] + r[k + 1]) / 2
  }
  function median(list,   a, n, i, j, t, k) {
    n = split(list, a, ";")
    for (i = 2; i <= n; i++) for (j = i; j > 1 && a[j - 1] > a[j]; j--) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
    k = int((n + 1) / 2); return n % 2 ? a[k] : (a[k] + a[k + 1]) / 2
  }'
ratio_to_shading() {  # CSV -> time / shading time per model and shape, per round
  awk -F, -v models="$models" -v shapes="$shapes" "$ratio_awk"'
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { v[$(idx["model"]) "," $(idx["shape"])] = $(idx["render_times_s"]) }
    END {
      ns = split(shapes, s, ","); nm = split(models, m, ",")
      printf "| model |"; for (j = 1; j <= ns; j++) printf " %s |", s[j]; printf "\n|---|"
      for (j = 1; j <= ns; j++) printf "---:|"; printf "\n"
      for (i = 2; i <= nm; i++) {
        printf "| %s |", m[i]
        for (j = 1; j <= ns; j++) {
          r = ratio(v[m[i] "," s[j]], v["shading," s[j]]); printf " %.2f (%.2f-%.2f) |", r, LO, HI
        }
        printf "\n"
      }
    }' "$1"
}
primitives_table() {
  awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    $1 == "shading" || $1 == "quadric-edges" || $1 == "quadric-param" || $1 == "quadric-implicit" {
      if (!($(idx["mesh"]) in seen)) { seen[$(idx["mesh"])] = 1; order[++n] = $(idx["mesh"]) }
      if (!($1 in mseen)) { mseen[$1] = 1; morder[++nm] = $1 }
      p[$1 "," $(idx["mesh"])] = $(idx["primitives"]); b[$1 "," $(idx["mesh"])] = $(idx["memory_bytes"])
    }
    END {
      printf "| model |"; for (j = 1; j <= n; j++) printf " %s |", order[j]; printf "\n|---|"
      for (j = 1; j <= n; j++) printf "---:|"; printf "\n"
      for (i = 1; i <= nm; i++) {
        printf "| %s |", morder[i]
        for (j = 1; j <= n; j++) printf " %d (%.1f KiB) |", p[morder[i] "," order[j]], b[morder[i] "," order[j]] / 1024
        printf "\n"
      }
    }' docs/results/primitives.csv
}
metrics_table() {  # CSV -> the constraint metrics of every model
  awk -F, '
    NR == 1 { printf "|"; for (i = 1; i <= NF; i++) if (i != 2 && i != 6) printf " %s |", $i
              printf "\n|"; for (i = 1; i <= NF; i++) if (i != 2 && i != 6) printf "---|"; printf "\n"; next }
    { printf "|"; for (i = 1; i <= NF; i++) if (i != 2 && i != 6) {
        if ($i == "") printf " - |"; else if ($i ~ /^[-0-9.e+]+$/ && $i ~ /[.e]/) printf " %.3g |", $i
        else printf " %s |", $i }
      printf "\n" }' "$1"
}
scaling_table() {
  awk -F, "$ratio_awk"'
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { t[$(idx["shape"]) "," $(idx["model"])] = $(idx["render_s"])
      r[$(idx["shape"]) "," $(idx["model"])] = $(idx["render_times_s"])
      if ($(idx["model"]) == "quadric-implicit") { n[++k] = $(idx["shape"]); p[$(idx["shape"])] = $(idx["primitives"]) } }
    END {
      print "| mesh | patches | shading (s) | quadric-param (s) | quadric-implicit (s) | implicit / shading | implicit / param |"
      print "|---|---:|---:|---:|---:|---:|---:|"
      for (i = 1; i <= k; i++) { s = n[i]
        a = ratio(r[s ",quadric-implicit"], r[s ",shading"]); alo = LO; ahi = HI
        b = ratio(r[s ",quadric-implicit"], r[s ",quadric-param"])
        printf "| %s | %d | %.3f | %.3f | %.3f | %.2f (%.2f-%.2f) | %.2f (%.2f-%.2f) |\n", s, p[s],
          t[s ",shading"], t[s ",quadric-param"], t[s ",quadric-implicit"], a, alo, ahi, b, LO, HI }
    }' docs/results/times_scaling.csv
}
targets_table() {  # the speed and memory targets (docs/RESULTS.md), measured
  echo "| target | measured: median (range over rounds) | result |"
  echo "|---|---|---|"
  for setup in a b; do
    awk -F, -v setup="$setup" -v shapes="$shapes" "$ratio_awk"'
      NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
      { v[$(idx["model"]) "," $(idx["shape"])] = $(idx["render_times_s"]) }
      END { ns = split(shapes, s, ",")
        for (j = 1; j <= ns; j++) { x = ratio(v["quadric-implicit," s[j]], v["shading," s[j]])
          printf "| quadric-implicit / shading render time <= 1.5, setup (%s), %s | %.2f (%.2f-%.2f) | %s |\n",
            setup, s[j], x, LO, HI, (x <= 1.5 ? "pass" : "FAIL") } }' "docs/results/times_$setup.csv"
  done
  awk -F, "$ratio_awk"'
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { r[$(idx["shape"]) "," $(idx["model"])] = $(idx["render_times_s"])
      if ($(idx["model"]) == "quadric-implicit") { n[++k] = $(idx["shape"]); p[$(idx["shape"])] = $(idx["primitives"]) } }
    END { first = ratio(r[n[1] ",quadric-implicit"], r[n[1] ",shading"])
      for (i = 2; i <= k; i++) if (p[n[i]] >= 100000) {
        x = ratio(r[n[i] ",quadric-implicit"], r[n[i] ",shading"])
        printf "| flat scaling: implicit / shading at %d patches <= 1.2 x that at %d patches | %.2f / %.2f = %.2f | %s |\n",
          p[n[i]], p[n[1]], x, first, x / first, (x / first <= 1.2 ? "pass" : "FAIL")
        printf "| quadric-implicit / shading render time <= 1.5, also in the scaling scene (not a thesis scene), %d patches | %.2f (%.2f-%.2f) | %s |\n",
          p[n[i]], x, LO, HI, (x <= 1.5 ? "pass" : "FAIL") }
      if (p[n[k]] < 100000) printf "| flat scaling up to 100,000+ patches | largest icosphere has %d patches | FAIL |\n", p[n[k]] }' \
    docs/results/times_scaling.csv
  awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { b[$1 "," $(idx["mesh"])] = $(idx["memory_bytes"]); if (!($(idx["mesh"]) in seen)) { seen[$(idx["mesh"])] = 1; o[++n] = $(idx["mesh"]) } }
    END { for (j = 1; j <= n; j++) { x = b["quadric-param," o[j]] / b["quadric-implicit," o[j]]
      printf "| quadric-implicit geometry >= 100x smaller than the 4802-triangle tessellation (quadric-param), %s | %.0fx (%.1f KiB against %.1f KiB) | %s |\n",
        o[j], x, b["quadric-implicit," o[j]] / 1024, b["quadric-param," o[j]] / 1024, (x >= 100 ? "pass" : "FAIL") } }' \
    docs/results/primitives.csv
}

cpu=$(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || echo unknown)
{
  cat <<HEAD
# Reproducing the thesis' results

Generated by \`scripts/reproduce.sh --$mode\` on $(date -u +%Y-%m-%d) at commit
\`$(git rev-parse --short HEAD 2>/dev/null || echo unknown)\`, on $(nproc) cores of a
$cpu (a machine shared with other jobs: single renders scatter by tens of percent, so every
ratio below is the median of side-by-side ratios over several rounds, with their range).
The CSVs behind every table are in [results/](results/). The thesis' numbers come from its
chapter 5 (Mitsuba 0.5 on an i5 4690k, 64 spp and 500 spp at its own, unstated resolution);
only ratios between models can be compared, not absolute times.

## Figure 5.1: diffuse objects, point light (setup a)

![figure 5.1](images/fig5_1_diffuse.png)

## Figure 5.2: glass objects, area light, adaptive sampling (setup b)

![figure 5.2](images/fig5_2_glass.png)

## Table 5.1: primitives per model (thesis tessellation, 4802 triangles per patch)

quadtri (\`quadtri analyze SHAPE --tessellation thesis --csv\`; in brackets the geometry memory):

$(primitives_table)

Thesis:

| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 1 | 4 | 20 |
| quadric-edges | 4802 | 19208 | 96040 |
| quadric-param | 4802 | 19208 | 96040 |
| quadric-implicit | 1 | 4 | 20 |

## Table 5.2: render time, setup (a)

quadtri, seconds (\`quadtri figure --setup a ${grid_a[*]}\`; render only, the
acceleration structure's build is in build_s of the CSV):

$(pivot docs/results/times_a.csv render_s 1 %.2f)

Ratio to \`shading\`, quadtri: the median over the rounds of the ratio of renders done side by
side, and its range over the rounds:

$(ratio_to_shading docs/results/times_a.csv)

Thesis, seconds, and ratio to shading:

| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 40.17 (1.00) | 43.97 (1.00) | 52.11 (1.00) |
| quadric-edges | 67.46 (1.68) | 93.82 (2.13) | 100.30 (1.92) |
| quadric-param | 72.50 (1.80) | 90.62 (2.06) | 112.14 (2.15) |
| quadric-implicit | 50.21 (1.25) | 71.62 (1.63) | 165.32 (3.17) |

## Table 5.3: render time, setup (b)

quadtri, seconds (\`quadtri figure --setup b ${grid_b[*]}\`):

$(pivot docs/results/times_b.csv render_s 1 %.2f)

Mean samples per pixel the adaptive integrator took:

$(pivot docs/results/times_b.csv spp 1 %.1f)

Ratio to \`shading\`, quadtri (median over rounds, and range):

$(ratio_to_shading docs/results/times_b.csv)

Thesis, hours, and ratio to shading:

| model | triangle | tetrahedron | icosahedron |
|---|---:|---:|---:|
| shading | 0.2882 (1.00) | 0.6134 (1.00) | 2.0992 (1.00) |
| quadric-edges | 1.6140 (5.60) | 5.3269 (8.68) | 7.7267 (3.68) |
| quadric-param | 1.7650 (6.12) | 3.5300 (5.75) | 6.6993 (3.19) |
| quadric-implicit | 1.4336 (4.97) | 3.4404 (5.61) | 10.6203 (5.06) |

## Figure 5.5 extended: render-time ratio as the patches grow

![figure 5.5](images/fig5_5_ratio.png)

\`quadtri figure --setup scaling --shapes icosphere-0..$levels --models shading,quadric-param,quadric-implicit ${scaling[*]} --ratio-plot ...\`
(quadric-param tessellated at the scene default, lattice level 8 = 64 triangles per patch;
times are medians of the rounds, ratios the median of per-round ratios, range in brackets):

$(scaling_table)

The thesis' figure 5.5 has two points per setup: quadric-param (4802 triangles per patch) /
quadric-implicit fell from 1.444 with one patch to 0.678 with 20 patches.

## Speed and memory targets

Render-time ratios are side by side (same round), medians over the rounds; memory from table 5.1.

$(targets_table)

## Figures 5.3 and 5.4: the parametric models at corners-only and 2500-point tessellations

\`quadtri analyze SHAPE --heatmaps DIR\` (\`MODEL-view-corners.png\`, \`MODEL-view-2500.png\`):
normal as colour (each component mapped from its range over the model, thesis §5.2), patch
boundaries and silhouette in black. With the 3 corner points per patch (figure 5.3) the
tessellation is the input mesh (constraints 1 and 2); with the thesis' 50x50 = 2500 points
(figure 5.4) the patches bulge and meet without gaps (constraint 3), the normal is continuous at
the vertices but kinks across the edges (constraint 4 holds at the vertices only).

| | tetrahedron, quadric-edges | tetrahedron, quadric-param | icosahedron, quadric-edges | icosahedron, quadric-param |
|---|---|---|---|---|
| corners only (5.3) | ![](images/fig5_3_4_tetrahedron-quadric-edges-corners.png) | ![](images/fig5_3_4_tetrahedron-quadric-param-corners.png) | ![](images/fig5_3_4_icosahedron-quadric-edges-corners.png) | ![](images/fig5_3_4_icosahedron-quadric-param-corners.png) |
| 2500 points (5.4) | ![](images/fig5_3_4_tetrahedron-quadric-edges-2500.png) | ![](images/fig5_3_4_tetrahedron-quadric-param-2500.png) | ![](images/fig5_3_4_icosahedron-quadric-edges-2500.png) | ![](images/fig5_3_4_icosahedron-quadric-param-2500.png) |

## Figures 5.6 and 6.2: the implicit model against its parametric patch

Per patch (patches laid out in cells, corner 0 bottom left), (f_i o f_p)(u, v) / |grad f_i|
divided by the mean edge length, and |n_p x n_i|, for \`quadric-implicit\`
(\`quadtri analyze icosahedron --heatmaps DIR\`, \`quadtri analyze data/teapot.obj --normals average --model quadric-implicit --heatmaps DIR\`).

Figure 5.6, icosahedron:

![figure 5.6a](images/fig5_6_icosahedron-residual.png)
![figure 5.6b](images/fig5_6_icosahedron-normal-misfit.png)

Figure 6.2, teapot:

![figure 6.2a](images/fig6_2_teapot-residual.png)
![figure 6.2b](images/fig6_2_teapot-normal-misfit.png)

## Constraint metrics (icosahedron, \`quadtri analyze icosahedron --csv\`)

$(metrics_table docs/results/icosahedron_metrics.csv)

## Teapot (\`quadtri analyze data/teapot.obj --normals average --csv\`)

$(metrics_table docs/results/teapot_metrics.csv)

## Every model on the teapot and the torus

Setups (a) and (b) as above (\`quadtri figure --shapes teapot,torus --models all eleven\`),
the torus a coarse 24×12 one (576 triangles) so that facets, terminators and cracks show.

![every model, setup (a)](images/models_a.png)
![every model, setup (b)](images/models_b.png)

HEAD
  [ -f docs/results/models.md ] && { cat docs/results/models.md; echo; }
  cat docs/results-discussion.md
} > docs/RESULTS.md.tmp
mv docs/RESULTS.md.tmp docs/RESULTS.md
echo "wrote docs/RESULTS.md"
