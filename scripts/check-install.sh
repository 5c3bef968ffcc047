#!/usr/bin/env bash
# Installs a built quadtri into a temporary prefix, builds examples/consumer against it with
# find_package(quadtri), and checks what the consumer prints: a ray straight down through
# (0.1, 0.05) onto the unit icosphere under quadric-implicit-robust, which reproduces the
# sphere, hits it at z = sqrt(1 - 0.1² - 0.05²) with the normal (0.1, 0.05, z).
#   scripts/check-install.sh [BUILD_DIR]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cmake --install "$build" --prefix "$work/prefix" >/dev/null
test -f "$work/prefix/include/quadtri/surface/model.h"
test -x "$work/prefix/bin/quadtri"
pc=
for f in "$work"/prefix/lib/pkgconfig/quadtri.pc "$work"/prefix/lib/*/pkgconfig/quadtri.pc; do
  if [ -f "$f" ]; then pc=$f; fi
done
test -n "$pc"
# pkg-config's flags name the prefix given to --install (the .pc file is relocatable): the
# consumer builds with them alone.
flags=$(PKG_CONFIG_PATH=$(dirname "$pc") pkg-config --cflags --libs quadtri)
case "$flags" in *"$work/prefix"*) ;; *) echo "install: pkg-config names no prefix: $flags" >&2; exit 1 ;; esac
c++ -std=c++20 -O1 examples/consumer/main.cpp -o "$work/consumer-pc" $flags
"$work/consumer-pc" icosphere:1 quadric-implicit-robust | grep -q "hit z = 0.99373"
echo "install: consumer built with pkg-config's flags alone"
cmake -S examples/consumer -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCMAKE_PREFIX_PATH="$work/prefix" >/dev/null
cmake --build "$work/consumer" >/dev/null
out=$("$work/consumer/quadtri_consumer" icosphere:1 quadric-implicit-robust)
echo "$out"
python3 - "$out" <<'PY'
import re, sys
m = re.search(r"hit z = ([-0-9.e]+), normal \(([-0-9.e]+), ([-0-9.e]+), ([-0-9.e]+)\)", sys.argv[1])
assert m, "consumer printed no hit"
z, nx, ny, nz = map(float, m.groups())
want = (1 - 0.1**2 - 0.05**2) ** 0.5
assert abs(z - want) < 1e-6, f"hit z {z}, expected {want} (the unit sphere)"
assert max(abs(nx - 0.1), abs(ny - 0.05), abs(nz - want)) < 1e-5, f"normal ({nx},{ny},{nz})"
print(f"install: consumer built against the installed package; hit the sphere at z = {want:.9f}")
PY
# The installed command renders: it finds its image module (the only part that links
# OpenImageIO) in the prefix's lib/quadtri/, with no build tree to fall back on.
"$work/prefix/bin/quadtri" render scenes/default.xml --spp 1 --crop 0,0,16,12 --threads 2 \
  -o "$work/crop.exr" >/dev/null
test -s "$work/crop.exr"
# merge reads the tile back through the module and refuses it: one window is not the film.
if "$work/prefix/bin/quadtri" merge "$work/crop.exr" -o "$work/merged.exr" 2>"$work/merge.err"; then
  echo "install: merge took one 16x12 window for the whole film" >&2
  exit 1
fi
grep -q "does not cover" "$work/merge.err" || { cat "$work/merge.err" >&2; exit 1; }
echo "install: the installed quadtri rendered a window of the default scene to EXR"
# The Python module, when built: imported from the prefix, the same ray cast from Python.
if [ -d "$work/prefix/lib/python3/dist-packages/quadtri" ]; then
  py=$(sed -n 's/^Python_EXECUTABLE:[A-Z]*=//p' "$build/CMakeCache.txt")
  PYTHONPATH="$work/prefix/lib/python3/dist-packages" "${py:-python3}" - <<'PY'
import quadtri
m = quadtri.Model("quadric-implicit-robust", *quadtri.load_mesh("icosphere:1"))
hit = quadtri.RayScene([m]).cast_rays([0.1, 0.05, 3.0], [0.0, 0.0, -1.0])
z = 3.0 - hit["t"][0]
want = (1 - 0.1**2 - 0.05**2) ** 0.5
assert abs(z - want) < 1e-9, f"hit z {z}, expected {want}"
assert "/dist-packages/quadtri/" in quadtri.__file__, quadtri.__file__
print(f"install: the Python module imports from the prefix; hit the sphere at z = {z:.9f}")
PY
fi
