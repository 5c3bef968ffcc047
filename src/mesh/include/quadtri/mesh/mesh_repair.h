// What a mesh file's defects become (README "Bad geometry"): the ones no model can use are
// removed, the ones that still join the surface are kept and counted, and the caller reports
// both.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace quadtri {

struct TriangleMesh;

/// Counts of what repairMesh (and the loader before it) did to a mesh.
struct MeshRepairs {
  // Repaired.
  size_t replacedNormals = 0;   ///< NaN, infinite or zero-length file normals → face normal
  size_t isolatedVertices = 0;  ///< vertices no triangle uses, removed
  size_t collapsedFaces = 0;    ///< triangles naming one vertex twice (no area), removed
  size_t duplicateFaces = 0;    ///< the same three vertices as an earlier triangle, removed
  size_t reorientedFaces = 0;   ///< re-wound to agree with the rest of their part
  // Kept, and reported.
  size_t zeroAreaFaces = 0;       ///< three distinct collinear vertices: they still join neighbours
  size_t nonManifoldEdges = 0;    ///< edges with three or more triangles
  size_t nonOrientableParts = 0;  ///< connected parts no winding makes consistent (Möbius)

  bool any() const;
  /// One sentence, "" when there is nothing to report, e.g. "removed 2 duplicate triangles and
  /// 1 isolated vertex; kept 3 edges with three or more triangles (crack_rate is undefined)".
  std::string summary() const;
};

/// Removes collapsed and duplicate triangles (the first of each set of three vertices stays,
/// whatever its winding: a surface cannot be two patches at once; use a twosided BSDF for a
/// sheet seen from both sides) and then the vertices no triangle uses, renumbering the rest in
/// order. Then re-winds the triangles of each connected part whose winding is inconsistent
/// (two triangles sharing a two-sided edge must run along it in opposite directions) to the
/// winding of most of the part's area, swapping a flipped triangle's corners 1 and 2; only in a
/// mesh without normals, since file normals say which side is out. Counts
/// zero-area triangles, non-manifold edges and non-orientable parts, which stay. Adds to
/// `mesh.repairs` and returns what this call did. Triangles keep their order otherwise, and a
/// mesh without defects is left bitwise unchanged. `significandBits` is the precision the
/// coordinates were read in (24: floats, as Assimp reads them; 53: doubles, the native OBJ and
/// OFF readers and arrays): a triangle counts as zero-area when its third vertex lies within a
/// few units of that precision (4 for floats, 16 for doubles, above the rounding of the cross
/// product), at the triangle's largest coordinate, of its longest edge's line.
MeshRepairs repairMesh(TriangleMesh& mesh, int significandBits = 53);

/// "WHAT: removed …; kept …" when the loader repaired or kept a defect of `mesh`, for the
/// caller to print as a warning.
std::optional<std::string> repairWarning(const TriangleMesh& mesh, std::string_view what);

}  // namespace quadtri
