// An indexed triangle mesh with welded positions and per-corner shading normals.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "quadtri/math/fnv1a.h"
#include "quadtri/math/vec.h"
#include "quadtri/mesh/mesh_repair.h"

namespace quadtri {

using Tri = std::array<uint32_t, 3>;

struct MeshTopology;
struct TriangleMesh;

/// A mesh's edge adjacency, built on first request and then kept with the mesh, so that the
/// loader's repair, the normals, a model, its metrics and its tessellation share one (derived
/// quantities on request, as geometry-central's require*() calls). Copying a mesh does not copy
/// it: the copy builds its own when asked, so a copy may be edited freely. Requests from
/// several threads are safe; the adjacency is built outside any lock (building it runs parallel
/// loops, and a thread waiting on a lock inside one could be asked to run the other request).
class TopologyCache {
 public:
  TopologyCache();
  ~TopologyCache();
  TopologyCache(const TopologyCache&);
  TopologyCache& operator=(const TopologyCache&);
  TopologyCache(TopologyCache&&) noexcept;
  TopologyCache& operator=(TopologyCache&&) noexcept;

  /// The adjacency of `mesh` (the mesh that holds this cache).
  const MeshTopology& get(const TriangleMesh& mesh) const;
  /// Keeps `topology`, already built from `mesh`'s triangles as they are now.
  void keep(const TriangleMesh& mesh, std::shared_ptr<const MeshTopology> topology);
  /// Drops what was kept (after the mesh's triangles changed in place).
  void forget();
  /// How many times this cache built an adjacency (for tests of "built once").
  size_t builds() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

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
  /// The digest of the file's bytes as loadMesh read them (render keys use it instead of
  /// reading the file again); zero for a mesh not read from a file.
  FileDigest fileDigest;

  size_t triangleCount() const { return triangles.size(); }
  bool hasNormals() const { return !normalIndices.empty(); }

  const Vec3& corner(size_t t, int k) const { return positions[triangles[t][k]]; }
  /// Shading normal at corner k of triangle t (the face normal when the mesh has none).
  Vec3 cornerNormal(size_t t, int k) const;
  /// cornerNormal normalised, or faceNormal where it has no length: what safeNormalized(
  /// cornerNormal(t, k), faceNormal(t)) gives, without computing the face normal every time.
  Vec3 unitCornerNormal(size_t t, int k) const;
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

  /// The edge adjacency of the triangles, built once (TopologyCache). Code that edits
  /// `triangles` in place after asking for it calls topologyCache.forget(); a mesh whose
  /// triangle array was replaced or resized is rebuilt on its own.
  const MeshTopology& topology() const { return topologyCache.get(*this); }
  TopologyCache topologyCache;
};

}  // namespace quadtri
