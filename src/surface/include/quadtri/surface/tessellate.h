// Triangle meshes from patches: the render geometry of the tessellated models.
#pragma once

#include <string>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/model.h"

namespace quadtri {

/// How finely each patch is tessellated.
struct Tessellation {
  enum class Kind {
    Lattice,     ///< triangle lattice of level n: (n+1)(n+2)/2 points, n² triangles per patch
    ThesisGrid,  ///< the thesis' 50×50 uv grid: 2500 points, 4802 triangles per patch (Table 5.1)
  } kind = Kind::Lattice;
  int level = 8;

  static Tessellation thesis() { return {Kind::ThesisGrid, 50}; }
  /// Parses "N" (lattice level) or "thesis".
  static Tessellation parse(const std::string& text);
  size_t trianglesPerPatch() const;
};

/// Evaluates every patch of `model` on the tessellation's points and triangulates them. Vertex
/// normals are the model's surface normals. When model.sharesEdges(), points on a mesh edge and
/// at mesh vertices are created once and shared by both patches (welded), so the tessellation
/// of a closed mesh is closed; where the mesh splits normals (on such an edge or at such a
/// vertex) each patch keeps its own surface normal there (per-corner normals), so a crease
/// stays sharp in shading. InputTriangles models return their mesh unchanged.
TriangleMesh tessellate(const SurfaceModel& model, const Tessellation& tessellation);

}  // namespace quadtri
