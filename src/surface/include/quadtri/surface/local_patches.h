// What the local-interpolation models (phong, pn, nagata) share: each patch is built from one
// triangle's corners and corner normals (and, where the mesh splits normals, the data its edges'
// sides share: creases.h).
#pragma once

#include <array>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// The corners and unit corner normals of one triangle, the only input of a local patch.
struct LocalTriangle {
  std::array<Vec3, 3> p;
  std::array<Vec3, 3> n;
};

/// Triangle t's corners and its corner normals, renormalised so formulas that assume unit
/// normals (tangent-plane projections, PN's w_ij) hold to round-off.
LocalTriangle localTriangle(const TriangleMesh& mesh, size_t t);

/// The unit geometric normal ±(du × dv)/|du × dv| of patch t, signed like patchOrientation so
/// it lies on the side of the shading normals. Where du × dv vanishes (a degenerate triangle)
/// it falls back to the barycentric blend of the corner normals (u, v), then the face normal.
Vec3 orientedPatchNormal(const TriangleMesh& mesh, size_t t, double u, double v, const Vec3& du,
                         const Vec3& dv);

struct QuadraticPatch;
struct QuadricPatch;
class PatchRecord;
/// Adds {"vertices", "control_points": {b01, b12, b20}} of a quadratic Bézier patch.
void addControlNet(const QuadraticPatch& patch, PatchRecord& out);
/// Adds {"vertices", "control_points": {b01, b12, b20}, "coefficients": {c0..c5}} of a quadratic
/// Bézier patch (the thesis' §4.2 parametric triangle) to a patch record, shared by every model
/// built on one.
void addQuadraticPatch(const QuadraticPatch& patch, PatchRecord& out);
/// Adds {"quadric": [A..J], "planes": [[nx, ny, nz, d]...], "bounds": {min, max},
/// "orientation"} to a patch record.
void addQuadricPatch(const QuadricPatch& patch, PatchRecord& out);
/// Adds "vertices": [[x, y, z] × 3], the corners of triangle t.
void addVertices(const TriangleMesh& mesh, size_t t, PatchRecord& out);

}  // namespace quadtri
