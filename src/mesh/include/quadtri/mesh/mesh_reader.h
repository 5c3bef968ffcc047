// The choice of reader behind loadMesh (mesh_io.h).
#pragma once

#include <filesystem>

#include "quadtri/mesh/mesh_io.h"

namespace quadtri {

/// Auto: a plain OBJ file (only v lines of x y z, vn, vt, faces of three corners, s lines and
/// whole-line comments; every corner with a normal or none) is read by quadtri's own reader,
/// which gives the mesh Assimp's OBJ importer gives, bit for bit (its number parser, one vertex
/// per corner in face order), in a fraction of its time; every other OBJ, PLY or STL file is read
/// by Assimp. Every OFF file is read by quadtri's own reader (off_reader.cpp: ASCII
/// [ST][C][N]OFF read line by line as scripts/corpus-manifest.py reads it, polygons cut into
/// k - 2 triangles); Assimp's OFF importer failed on some of the corpus's files.
/// Assimp: Assimp reads every file (tests compare the two).
enum class MeshReader { Auto, Assimp };

/// loadMesh with the reader chosen; loadMesh is loadMeshWith(MeshReader::Auto, ...).
TriangleMesh loadMeshWith(MeshReader reader, const std::filesystem::path& path,
                          const NormalOptions& normals = {}, MemoryBudget* budget = nullptr);

}  // namespace quadtri
