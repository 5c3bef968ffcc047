// Mesh import (OBJ, PLY, STL through Assimp; OFF, plain OBJ natively) and export (OBJ, PLY).
#pragma once

#include <filesystem>
#include <functional>
#include <vector>

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

/// A mesh that saveMeshStream writes block by block, never whole: with normals, one per point
/// (normal i is point i's) and `extraNormals` more after them, each at one of the points; or
/// none. The blocks' points, in block order, are points 0 to `points` - 1; their extra normals,
/// in block order, normals `points` on; their triangles, in block order, the mesh's.
struct MeshStream {
  size_t points = 0, extraNormals = 0, triangles = 0, blocks = 0;
  bool hasNormals = true;
  /// Appends block b's points to positions and (with normals) normals.
  std::function<void(size_t b, std::vector<Vec3>& positions, std::vector<Vec3>& normals)>
      blockPoints;
  /// Appends block b's extra normals, and the position of the point each is at (needed when
  /// extraNormals > 0).
  std::function<void(size_t b, std::vector<Vec3>& positions, std::vector<Vec3>& normals)>
      blockExtraNormals;
  /// Appends block b's triangles and, where some corner takes an extra normal, every corner's
  /// normal index (left empty: each corner's normal is its point's).
  std::function<void(size_t b, std::vector<Tri>& triangles, std::vector<Tri>& normalIndices)>
      blockTriangles;
};

/// Writes such a mesh as saveMesh writes it, a block at a time: an OBJ file the bytes saveMesh
/// writes for the whole mesh; a PLY file with a vertex per normal, in normal order (a point's
/// own, then the extra ones at their points; saveMesh numbers them by first use). OBJ's points
/// are asked for twice, for their positions and then their normals. The file appears
/// atomically; nothing is written when a block has a non-finite position or the blocks do not
/// hold the counts.
void saveMeshStream(const MeshStream& mesh, const std::filesystem::path& path);

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
