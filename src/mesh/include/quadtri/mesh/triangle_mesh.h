// An indexed triangle mesh with welded positions and per-corner shading normals.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "quadtri/math/vec.h"
#include "quadtri/mesh/mesh_repair.h"

namespace quadtri {

using Tri = std::array<uint32_t, 3>;

/// Positions are welded (one index per distinct point), so adjacency follows from the indices.
/// Shading normals are per corner: corner k of triangle t has normal normals[normalIndices[t][k]],
/// so split normals at a crease stay split while positions stay shared.
struct TriangleMesh {
  std::vector<Vec3> positions;
  std::vector<Tri> triangles;
  std::vector<Vec3> normals;       ///< unit shading normals, shared by corners that index them
  std::vector<Tri> normalIndices;  ///< one per triangle; empty means "no shading normals"
  /// What the loader repaired or found (mesh_repair.h); all zero for a built mesh.
  MeshRepairs repairs;

  size_t triangleCount() const { return triangles.size(); }
  bool hasNormals() const { return !normalIndices.empty(); }

  const Vec3& corner(size_t t, int k) const { return positions[triangles[t][k]]; }
  /// Shading normal at corner k of triangle t (the face normal when the mesh has none).
  Vec3 cornerNormal(size_t t, int k) const;
  /// Unit geometric normal (v1-v0)×(v2-v0), or +z for a zero-area triangle.
  Vec3 faceNormal(size_t t) const;
  /// Twice the triangle's area vector, (v1-v0)×(v2-v0).
  Vec3 faceCross(size_t t) const;

  Bounds3 bounds() const;
  double meanEdgeLength() const;
  /// Mean length of triangle t's three edges.
  double meanEdgeLength(size_t t) const;

  /// Checks indices, finiteness and normal layout; throws Error naming the element otherwise.
  void validate(const std::string& what) const;
};

}  // namespace quadtri
