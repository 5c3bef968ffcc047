#!/usr/bin/env bash
# Fetches the Utah teapot (npm package `teapot`: 792 vertices, 992 triangles, public domain) and
# writes it as an OBJ without normals (the thesis scenes and scripts give it thesis eq. 2.8 normals
# with --normals average / normals="average"). Idempotent.
# Usage: scripts/fetch-teapot.sh OUT.obj
set -euo pipefail
out=${1:-data/teapot.obj}
[ -s "$out" ] && exit 0
mkdir -p "$(dirname "$out")"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
(cd "$work" && npm pack --silent teapot@1.0.0 >/dev/null 2>&1 && tar xzf teapot-1.0.0.tgz)
node -e '
const t = require(process.argv[1]);
const lines = ["# Utah teapot from the npm package teapot@1.0.0 (public domain)"];
for (const p of t.positions) lines.push("v " + p.join(" "));
for (const c of t.cells) lines.push("f " + c.map(i => i + 1).join(" "));
require("fs").writeFileSync(process.argv[2], lines.join("\n") + "\n");
' "$work/package/teapot.js" "$out.tmp"
mv "$out.tmp" "$out"
