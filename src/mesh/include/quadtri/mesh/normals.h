// Vertex shading normals for meshes whose file has none.
#pragma once

#include <string_view>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

enum class NormalSource {
  File,     ///< keep the file's normals (computed by `Average` when the file has none)
  Average,  ///< thesis eq. 2.8: normalised sum of the unit normals of the adjacent faces
  Angle,    ///< face normals weighted by the corner angle (Thürmer and Wüthrich 1998)
};

NormalSource parseNormalSource(std::string_view name);

/// Replaces the mesh's normals by one smooth normal per vertex. A vertex whose weighted sum
/// vanishes (e.g. a needle of opposite faces) gets the normal of its first adjacent face.
void computeVertexNormals(TriangleMesh& mesh, NormalSource source);

}  // namespace quadtri
