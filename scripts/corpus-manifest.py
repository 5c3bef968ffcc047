#!/usr/bin/env python3
"""Regenerates data/corpus-manifest.csv and data/corpus-skipped.txt from a fetched corpus.

Usage: scripts/corpus-manifest.py [CORPUS] [--check]

CORPUS defaults to $QUADTRI_CORPUS, else corpus/ at the repository root (scripts/fetch-corpus.sh
fills it). --check writes nothing and exits 1 when the files in data/ differ from what the
corpus gives. Only the standard library: reads OFF (OFF, COFF, NOFF, ... ASCII), OBJ, PLY
(ASCII and binary) and STL (ASCII and binary).

The counts follow what quadtri sees (src/mesh/mesh_io.cpp): polygons are fan-triangulated
(n - 2 triangles each), faces of fewer than three corners dropped, and vertices welded when
their coordinates are equal as 32-bit floats (Assimp's precision); `vertices` counts the
welded vertices that some face uses. data/README.md defines the other columns.
"""

import csv
import io
import os
import re
import struct
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
MANIFEST = ROOT / "data" / "corpus-manifest.csv"
SKIPPED = ROOT / "data" / "corpus-skipped.txt"
COLUMNS = ["name", "path", "source", "licence", "triangles", "vertices", "closed", "manifold",
           "file_normals", "kind"]
MESH_EXTENSIONS = {".off", ".obj", ".ply", ".stl"}

CGAL_LICENCE = "CC0-1.0 (CGAL's rule for files without a notice; see data/README.md)"

# Mechanical: meant to be flat faces with sharp creases (CAD parts, boxes, polyhedra, letters,
# planar test sheets). Organic: meant to be smooth and curved (scans, sculpted models, smooth
# analytic surfaces, coarse control meshes of smooth shapes). Judged file by file (dihedral
# angles, distinct face normals, the name); data/README.md lists the doubtful ones.
MECHANICAL = {
    "ALSTOM_TEST4", "anchor", "anchor_dense", "beam", "blade", "boeing", "cheese", "cheese-box",
    "colored_tetra", "corner", "corner_poly", "corner_tris_with_hole", "corner_with_hole",
    "corner_with_sharp_edge", "couplingdown", "cross", "cross_quad", "cube", "cube-meshed",
    "cube-ouvert", "cube-shuffled", "cube4-shuffled", "cube_poly", "cube_quad", "cylinder",
    "cylinder_locally_refined", "degtri_sliding", "dragknob", "fandisk", "fandisk-box",
    "fandisk_large", "hedra", "hedra_open", "hole", "horizons-domain", "icosahedron", "in",
    "joint", "mech-holes-shark", "mesh_with_colors", "mpi", "mpi_triang", "oblong",
    "oblong-shuffled", "octahedron", "open_cube", "P", "part", "pinion", "pinion_small", "pipe",
    "plane", "prim", "pyramid", "quad", "quads_to_stitch", "reference_tetrahedron", "rotor",
    "rotor_small", "small_cube", "spool", "star", "tet-shuffled",
    "tetra_intersected_by_triangle", "tetrahedron", "translated-cube", "triangle",
    "triangular_hole", "turbine", "u",
}


class MeshError(Exception):
    pass


class Mesh:
    def __init__(self):
        self.positions = []   # (x, y, z) floats, as in the file
        self.faces = []       # lists of indices into positions
        self.file_normals = False


# --- readers ---------------------------------------------------------------------------------

def text_lines(data):
    """Lines of a text file, comments (#...) stripped, blank lines dropped."""
    for raw in data.decode("latin-1").splitlines():
        line = raw.split("#", 1)[0].strip()
        if line:
            yield line


def read_off(data):
    lines = list(text_lines(data))
    if not lines:
        raise MeshError("empty OFF file")
    words = lines[0].split()
    match = re.fullmatch(r"(ST)?(C)?(N)?(4)?(n)?OFF", words[0])
    if not match:
        raise MeshError(f"OFF header expected, found '{words[0]}'")
    if match.group(4) or match.group(5):
        raise MeshError(f"unsupported OFF variant '{words[0]}'")
    if len(words) > 1 and words[1].upper() == "BINARY":
        raise MeshError("binary OFF is not supported")
    rest = words[1:]
    body = lines[1:]
    if len(rest) < 2:
        rest = body[0].split()
        body = body[1:]
    nv, nf = int(rest[0]), int(rest[1])
    if len(body) < nv + nf:
        raise MeshError(f"OFF promises {nv} vertices and {nf} faces, has {len(body)} lines")
    mesh = Mesh()
    mesh.file_normals = match.group(3) is not None
    for line in body[:nv]:
        w = line.split()
        mesh.positions.append((float(w[0]), float(w[1]), float(w[2])))
    for line in body[nv:nv + nf]:
        w = line.split()
        n = int(w[0])
        mesh.faces.append([int(i) for i in w[1:1 + n]])
    return mesh


def read_obj(data):
    mesh = Mesh()
    normals = 0
    faces_with_normals = 0
    for line in text_lines(data):
        w = line.split()
        if w[0] == "v":
            mesh.positions.append((float(w[1]), float(w[2]), float(w[3])))
        elif w[0] == "vn":
            normals += 1
        elif w[0] == "f":
            face = []
            has_normals = True
            for corner in w[1:]:
                parts = corner.split("/")
                i = int(parts[0])
                face.append(i - 1 if i > 0 else len(mesh.positions) + i)
                has_normals = has_normals and len(parts) == 3 and parts[2] != ""
            mesh.faces.append(face)
            faces_with_normals += has_normals
    mesh.file_normals = normals > 0 and faces_with_normals == len(mesh.faces)
    return mesh


PLY_TYPES = {
    "char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
    "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
    "float": "f", "float32": "f", "double": "d", "float64": "d",
}


def read_ply(data):
    end = data.find(b"end_header")
    if not data.startswith(b"ply") or end < 0:
        raise MeshError("PLY header expected")
    body_start = data.index(b"\n", end) + 1
    elements = []  # [name, count, [(name, type) or (name, ('list', count_type, item_type))]]
    fmt = None
    for line in data[:end].decode("latin-1").splitlines()[1:]:
        w = line.split()
        if not w or w[0] in ("comment", "obj_info"):
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append([w[1], int(w[2]), []])
        elif w[0] == "property":
            if w[1] == "list":
                elements[-1][2].append((w[4], ("list", PLY_TYPES[w[2]], PLY_TYPES[w[3]])))
            else:
                elements[-1][2].append((w[2], PLY_TYPES[w[1]]))
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise MeshError(f"unknown PLY format '{fmt}'")

    if fmt == "ascii":
        tokens = iter(data[body_start:].decode("latin-1").split())

        def scalar(t):
            value = next(tokens)
            return float(value) if t in "fd" else int(value)
    else:
        order = "<" if fmt == "binary_little_endian" else ">"
        offset = body_start

        def scalar(t):
            nonlocal offset
            (value,) = struct.unpack_from(order + t, data, offset)
            offset += struct.calcsize(t)
            return value

    mesh = Mesh()
    for name, count, props in elements:
        names = [p[0] for p in props]
        if name == "vertex":
            xyz = [names.index(c) for c in "xyz"]
            mesh.file_normals = all(c in names for c in ("nx", "ny", "nz"))
        for _ in range(count):
            values = []
            for _pname, ptype in props:
                if isinstance(ptype, tuple):
                    n = scalar(ptype[1])
                    values.append([scalar(ptype[2]) for _ in range(n)])
                else:
                    values.append(scalar(ptype))
            if name == "vertex":
                mesh.positions.append(tuple(float(values[i]) for i in xyz))
            elif name == "face":
                for key in ("vertex_indices", "vertex_index"):
                    if key in names:
                        mesh.faces.append(values[names.index(key)])
    return mesh


def read_stl(data):
    mesh = Mesh()  # STL's facet normals are not vertex normals: quadtri ignores them
    if len(data) >= 84:
        (n,) = struct.unpack_from("<I", data, 80)
        if len(data) == 84 + 50 * n:
            for t in range(n):
                v = struct.unpack_from("<9f", data, 84 + 50 * t + 12)
                base = len(mesh.positions)
                mesh.positions += [v[0:3], v[3:6], v[6:9]]
                mesh.faces.append([base, base + 1, base + 2])
            return mesh
    face = []
    for line in text_lines(data):
        w = line.split()
        if w[0] == "vertex":
            face.append(len(mesh.positions))
            mesh.positions.append((float(w[1]), float(w[2]), float(w[3])))
        elif w[0] == "endloop":
            mesh.faces.append(face)
            face = []
    return mesh


READERS = {".off": read_off, ".obj": read_obj, ".ply": read_ply, ".stl": read_stl}


# --- topology --------------------------------------------------------------------------------

def f32(x):
    return struct.unpack("f", struct.pack("f", x))[0]


def analyse(mesh):
    """Triangles, welded vertices used, closed, manifold (see data/README.md)."""
    weld = {}
    ids = []
    for p in mesh.positions:
        key = (f32(p[0]), f32(p[1]), f32(p[2]))
        ids.append(weld.setdefault(key, len(weld)))
    triangles = []
    for face in mesh.faces:
        if len(face) < 3:
            continue
        for i in face:
            if not 0 <= i < len(ids):
                raise MeshError(f"face index {i} out of range (0..{len(ids) - 1})")
        f = [ids[i] for i in face]
        for k in range(1, len(f) - 1):
            triangles.append((f[0], f[k], f[k + 1]))
    edge_faces = {}
    for t, (a, b, c) in enumerate(triangles):
        for u, v in ((a, b), (b, c), (c, a)):
            if u != v:
                edge_faces.setdefault((min(u, v), max(u, v)), []).append(t)
    used = {v for t in triangles for v in t}
    edges_ok = all(len(f) <= 2 for f in edge_faces.values())
    closed = bool(triangles) and all(len(f) == 2 for f in edge_faces.values())
    return len(triangles), len(used), closed, edges_ok and vertices_manifold(triangles)


def vertices_manifold(triangles):
    """Whether the triangles around every vertex form one fan, joined across their edges."""
    around = {}
    for t, tri in enumerate(triangles):
        for v in set(tri):
            around.setdefault(v, []).append(t)
    for v, tris in around.items():
        # Union-find over the triangles at v, joined where two share an edge at v.
        parent = {t: t for t in tris}

        def find(t):
            while parent[t] != t:
                parent[t] = parent[parent[t]]
                t = parent[t]
            return t

        by_neighbour = {}
        for t in tris:
            for w in set(triangles[t]) - {v}:
                if w in by_neighbour:
                    parent[find(t)] = find(by_neighbour[w])
                else:
                    by_neighbour[w] = t
        if len({find(t) for t in tris}) > 1:
            return False
    return True


# --- the corpus ------------------------------------------------------------------------------

def first_line(path):
    with open(path, "rb") as f:
        return f.readline().decode("latin-1").strip()


def rows_and_skipped(corpus):
    rows, skipped = [], []
    cgal_stamp = (corpus / "cgal" / ".source")
    if not cgal_stamp.is_file():
        raise SystemExit(f"{cgal_stamp}: not found; run scripts/fetch-corpus.sh first")
    package = " ".join(cgal_stamp.read_text().split()[:2])  # libcgal-demo VERSION
    files = sorted((p for p in corpus.rglob("*") if p.is_file() and not p.name.startswith(".")),
                   key=lambda p: p.relative_to(corpus).as_posix())
    stems = {}
    for p in files:
        stems.setdefault(p.stem, []).append(p)
    for p in files:
        rel = p.relative_to(corpus).as_posix()
        ext = p.suffix.lower()
        if ext not in MESH_EXTENSIONS:
            skipped.append(f"{rel}: not a mesh file ({ext or 'no extension'})")
            continue
        try:
            mesh = READERS[ext](p.read_bytes())
            triangles, vertices, closed, manifold = analyse(mesh)
        except (MeshError, ValueError, IndexError, KeyError, struct.error) as e:
            skipped.append(f"{rel}: unreadable ({e})")
            continue
        if triangles == 0:
            skipped.append(f"{rel}: no faces ({len(mesh.positions)} vertices: a point set)")
            continue
        name = p.stem
        if len(stems[p.stem]) > 1 and ext != ".off":
            name += "_" + ext[1:]
        if rel.startswith("cgal/"):
            source = f"Debian {package} data/meshes/{rel[5:]}"
            licence = CGAL_LICENCE
            kind = "mechanical" if p.stem in MECHANICAL else "organic"
        else:
            m = re.fullmatch(r"# npm (\S+) license: (.*)", first_line(p))
            if not m:
                raise SystemExit(f"{p}: first line names no npm package; rerun fetch-corpus.sh")
            source, licence, kind = f"npm {m.group(1)}", m.group(2), "organic"
        row = [name, rel, source, licence, triangles, vertices, yes(closed), yes(manifold),
               yes(mesh.file_normals), kind]
        for field in row:
            if any(c in str(field) for c in ',"\n'):
                raise SystemExit(f"{rel}: field '{field}' has a comma or quote")
        rows.append(row)
    return rows, skipped


def yes(flag):
    return "yes" if flag else "no"


def main(argv):
    check = "--check" in argv
    args = [a for a in argv if a != "--check"]
    if len(args) > 1 or any(a.startswith("-") for a in args):
        raise SystemExit(__doc__.split("\n\n")[1])
    corpus = Path(args[0] if args else os.environ.get("QUADTRI_CORPUS") or ROOT / "corpus")
    rows, skipped = rows_and_skipped(corpus)
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(COLUMNS)
    writer.writerows(rows)
    outputs = {MANIFEST: out.getvalue(), SKIPPED: "".join(s + "\n" for s in skipped)}
    if check:
        stale = [p for p, text in outputs.items()
                 if not p.is_file() or p.read_text() != text]
        for p in stale:
            print(f"corpus-manifest: {p.relative_to(ROOT)} is out of date", file=sys.stderr)
        return 1 if stale else 0
    MANIFEST.parent.mkdir(exist_ok=True)
    for p, text in outputs.items():
        tmp = p.with_suffix(p.suffix + ".tmp")
        tmp.write_text(text)
        tmp.replace(p)
    print(f"corpus-manifest: {len(rows)} meshes, {len(skipped)} files skipped")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
