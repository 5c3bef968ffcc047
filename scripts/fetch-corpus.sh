#!/usr/bin/env bash
# Fetches the real-mesh corpus listed in data/corpus-manifest.csv into DEST (default:
# $QUADTRI_CORPUS, else corpus/ at the repository root):
#   DEST/cgal/  the files of CGAL's data/meshes/, as they are, from Debian's libcgal-demo
#               (its /usr/share/doc/libcgal-dev/data.tar.gz);
#   DEST/npm/   teapot.obj and bunny.obj, converted from the npm packages teapot and bunny
#               (JS modules exporting {positions, cells}).
# Then checks that every file the manifest lists is there and prints a one-line summary.
# Idempotent: a second run installs, extracts and downloads nothing. Needs root (or sudo) only
# when libcgal-demo is missing. scripts/corpus-manifest.py DEST regenerates the manifest.
# Usage: scripts/fetch-corpus.sh [DEST]
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
dest=${1:-${QUADTRI_CORPUS:-$root/corpus}}
manifest=$root/data/corpus-manifest.csv
archive=/usr/share/doc/libcgal-dev/data.tar.gz
npm_packages=(teapot@1.0.0 bunny@1.0.1)

# 1. Debian's libcgal-demo, only when missing.
if ! dpkg-query -W -f='${Status}' libcgal-demo 2>/dev/null | grep -q "install ok installed"; then
  echo "fetch-corpus: installing libcgal-demo" >&2
  as_root=(env DEBIAN_FRONTEND=noninteractive DEBCONF_NOWARNINGS=yes)
  if [ "$(id -u)" -ne 0 ]; then as_root=(sudo "${as_root[@]}"); fi
  "${as_root[@]}" apt-get update -qq
  "${as_root[@]}" apt-get install -y -qq --no-install-recommends libcgal-demo >/dev/null
fi
[ -s "$archive" ] || { echo "fetch-corpus: $archive not found" >&2; exit 1; }

[ -f "$manifest" ] || { echo "fetch-corpus: $manifest not found" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$dest/cgal" "$dest/npm"

# Manifest files not there yet: "cgal" or "npm" in this list forces that part to be redone.
# The manifest's fields hold no commas.
missing_parts() {
  while IFS=, read -r name path _rest; do
    [ "$name" = name ] || [ -s "$dest/$path" ] || echo "${path%%/*}"
  done <"$manifest" | sort -u
}
parts=$(missing_parts)

# 2. CGAL's meshes. The stamp, written last, names the package version (corpus-manifest.py
# reads it) and the archive they came from.
cgal_stamp=$dest/cgal/.source
cgal_id="$(dpkg-query -W -f='libcgal-demo ${Version}' libcgal-demo) $(stat -c '%s %Y' "$archive")"
if [ ! -f "$cgal_stamp" ] || [ "$(cat "$cgal_stamp")" != "$cgal_id" ] ||
   grep -qx cgal <<<"$parts"; then
  rm -f "$cgal_stamp"
  tar -xzf "$archive" -C "$work" --wildcards 'data/meshes/*'
  cp -a "$work/data/meshes/." "$dest/cgal/"
  printf '%s\n' "$cgal_id" >"$cgal_stamp"
fi

# 3. The npm meshes, as OBJ (1-based indices, no normals). The first line of each names the
# package, its version and its licence field (corpus-manifest.py reads it).
npm_stamp=$dest/npm/.source
npm_id=${npm_packages[*]}
if [ ! -f "$npm_stamp" ] || [ "$(cat "$npm_stamp")" != "$npm_id" ] ||
   grep -qx npm <<<"$parts"; then
  rm -f "$npm_stamp"
  npm install --silent --no-save --no-audit --no-fund --no-package-lock --prefix "$work" \
    "${npm_packages[@]}" >/dev/null
  cat >"$work/to-obj.js" <<'EOF'
// node to-obj.js PACKAGE_DIR OUT.obj: writes the package's {positions, cells} as an OBJ.
const fs = require("fs");
const path = require("path");
const [dir, out] = process.argv.slice(2);
const pkg = JSON.parse(fs.readFileSync(path.join(dir, "package.json"), "utf8"));
const label = pkg.name + "@" + pkg.version;
const mesh = require(path.resolve(dir));
if (!Array.isArray(mesh.positions) || !Array.isArray(mesh.cells))
  throw new Error(label + ": exports no {positions, cells} arrays");
const lines = ["# npm " + label + " license: " + (pkg.license || "none given")];
for (const p of mesh.positions) {
  if (p.length !== 3 || !p.every(Number.isFinite)) throw new Error(label + ": bad vertex " + p);
  lines.push("v " + p.join(" "));
}
for (const c of mesh.cells) {
  if (c.length < 3 || !c.every(i => Number.isInteger(i) && i >= 0 && i < mesh.positions.length))
    throw new Error(label + ": bad face " + c);
  lines.push("f " + c.map(i => i + 1).join(" "));
}
fs.writeFileSync(out + ".tmp", lines.join("\n") + "\n");
fs.renameSync(out + ".tmp", out);
EOF
  for p in "${npm_packages[@]}"; do
    node "$work/to-obj.js" "$work/node_modules/${p%@*}" "$dest/npm/${p%@*}.obj"
  done
  printf '%s\n' "$npm_id" >"$npm_stamp"
fi

# 4. Every file of the manifest must be there.
count=0 missing=0 triangles=0
while IFS=, read -r name path _source _licence tris _rest; do
  [ "$name" = name ] && continue
  count=$((count + 1))
  triangles=$((triangles + tris))
  if [ ! -s "$dest/$path" ]; then
    echo "fetch-corpus: missing $dest/$path ($name)" >&2
    missing=$((missing + 1))
  fi
done <"$manifest"
if [ "$missing" -ne 0 ]; then
  echo "fetch-corpus: $missing of $count manifest meshes missing in $dest" >&2
  exit 1
fi
echo "fetch-corpus: $count meshes, $triangles triangles, in $dest"
