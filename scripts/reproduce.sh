#!/usr/bin/env bash
# Reproduces the thesis' chapter 5 results (DESIGN.md §6) and writes docs/RESULTS.md,
# docs/images/*.png and docs/results/*.csv.
#
# Usage: scripts/reproduce.sh [--quick|--full]
#   --quick (default): 96x96 images, 32 spp in setup (a); 88x88, adaptive up to 64 spp in (b)
#                      icospheres of levels 0..6 (20 .. 81,920 patches) at 128x128, 16 spp.
#                      A few minutes on 2 cores.
#   --full:            the scenes' own settings: 256x256, 64 spp (a), adaptive up to 500 spp (b),
#                      icospheres of levels 0..7 (up to 327,680 patches) at 128x128, 16 spp, and
#                      the teapot in table 5.1 too. Hours on 2 cores.
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
  grid_a=(--res 96 --spp 32); grid_b=(--res 88 -D spp=64)
  levels=6; scaling=(--res 128 --spp 16); table_shapes="triangle tetrahedron icosahedron"
else
  grid_a=(); grid_b=(); levels=7; scaling=(); table_shapes="triangle tetrahedron icosahedron data/teapot.obj"
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
# Table 5.1 (thesis tessellation: 4802 triangles per patch) and the constraint metrics.
echo "model,mesh,triangles,primitives,memory_bytes,convert_seconds,vertex_position_error,vertex_normal_error_deg,c0_gap,c1_angle_deg,crack_rate,truth_distance" \
  > docs/results/primitives.csv
for s in $table_shapes; do
  "$quadtri" analyze "$s" --tessellation thesis --lines 200 --csv | tail -n +2 >> docs/results/primitives.csv
done
"$quadtri" analyze icosahedron --csv > docs/results/icosahedron_metrics.csv
"$quadtri" analyze data/teapot.obj --normals average --csv > docs/results/teapot_metrics.csv

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
ratio_to_shading() {  # CSV -> time / shading time per model and shape
  awk -F, -v models="$models" -v shapes="$shapes" '
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { v[$(idx["model"]) "," $(idx["shape"])] = $(idx["render_s"]) }
    END {
      ns = split(shapes, s, ","); nm = split(models, m, ",")
      printf "| model |"; for (j = 1; j <= ns; j++) printf " %s |", s[j]; printf "\n|---|"
      for (j = 1; j <= ns; j++) printf "---:|"; printf "\n"
      for (i = 1; i <= nm; i++) {
        printf "| %s |", m[i]
        for (j = 1; j <= ns; j++) printf " %.2f |", v[m[i] "," s[j]] / v["shading," s[j]]
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
  awk -F, '
    NR == 1 { for (i = 1; i <= NF; i++) idx[$i] = i; next }
    { t[$(idx["shape"]) "," $(idx["model"])] = $(idx["render_s"])
      if ($(idx["model"]) == "quadric-implicit") { n[++k] = $(idx["shape"]); p[$(idx["shape"])] = $(idx["primitives"]) } }
    END {
      print "| mesh | patches | shading (s) | quadric-param (s) | quadric-implicit (s) | implicit / shading | implicit / param |"
      print "|---|---:|---:|---:|---:|---:|---:|"
      for (i = 1; i <= k; i++) { s = n[i]
        printf "| %s | %d | %.3f | %.3f | %.3f | %.2f | %.2f |\n", s, p[s], t[s ",shading"],
          t[s ",quadric-param"], t[s ",quadric-implicit"], t[s ",quadric-implicit"] / t[s ",shading"],
          t[s ",quadric-implicit"] / t[s ",quadric-param"] }
    }' docs/results/times_scaling.csv
}

cpu=$(awk -F': ' '/model name/ { print $2; exit }' /proc/cpuinfo 2>/dev/null || echo unknown)
{
  cat <<HEAD
# Reproducing the thesis' results

Generated by \`scripts/reproduce.sh --$mode\` on $(date -u +%Y-%m-%d) at commit
\`$(git rev-parse --short HEAD 2>/dev/null || echo unknown)\`, on $(nproc) cores of a
$cpu (a machine shared with other jobs, so times carry noise of some 10-20 %).
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

Ratio to \`shading\`, quadtri:

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

Ratio to \`shading\`, quadtri:

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
(quadric-param tessellated at the scene default, lattice level 8 = 64 triangles per patch):

$(scaling_table)

The thesis' figure 5.5 has two points per setup: quadric-param (4802 triangles per patch) /
quadric-implicit fell from 1.444 with one patch to 0.678 with 20 patches.

## Constraint metrics (icosahedron, \`quadtri analyze icosahedron --csv\`)

$(metrics_table docs/results/icosahedron_metrics.csv)

## Teapot (\`quadtri analyze data/teapot.obj --normals average --csv\`)

$(metrics_table docs/results/teapot_metrics.csv)

HEAD
  cat docs/results-discussion.md
} > docs/RESULTS.md.tmp
mv docs/RESULTS.md.tmp docs/RESULTS.md
echo "wrote docs/RESULTS.md"
