// Mesh import (OBJ, PLY, STL through Assimp; OFF, plain OBJ natively) and export (OBJ, PLY).
#pragma once

#include <filesystem>

#include "quadtri/mesh/mesh_io_check.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// Loads every mesh in the file as one triangle mesh. Positions are welded by exact equality
/// so adjacency is known; per-corner normals are kept as the file gives them (STL facet
/// normals are not shading normals and are ignored). `normals` picks the shading normals
/// (applyNormals): with File, a file without normals gets angle-weighted normals split at the
/// crease angle. Throws Error naming the file on failure. Before a reader reads the file,
/// inspectMeshFile checks its header's counts against its size and, given a budget,
/// chargeMeshFile refuses a mesh whose load and model would exceed it (mesh_reader.h: readers).
TriangleMesh loadMesh(const std::filesystem::path& path, const NormalOptions& normals = {},
                      MemoryBudget* budget = nullptr);

/// Writes OBJ or PLY (binary little-endian) by extension, with normals when the mesh has them.
/// The file appears atomically.
void saveMesh(const TriangleMesh& mesh, const std::filesystem::path& path);

}  // namespace quadtri

#include "quadtri/mesh/shapes.h"

namespace quadtri {

/// A mesh named on the command line: an existing file, or a built-in shape spec such as
/// `icosphere:3` (shapes.h). For a file, `normals` picks the normals as for loadMesh; for a
/// built-in shape, File keeps its analytic normals and Average/Angle recompute them. A budget is
/// charged as by loadMesh; a built-in shape, built first, is charged its model's bytes per
/// triangle.
BuiltinMesh loadMeshSpec(const std::string& spec, const NormalOptions& normals = {},
                         MemoryBudget* budget = nullptr);

}  // namespace quadtri
