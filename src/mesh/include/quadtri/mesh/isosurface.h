// Closed triangle meshes of implicit surfaces f = 0: marching tetrahedra over a regular grid,
// welded and consistently oriented, with every vertex projected onto the surface.
#pragma once

#include <functional>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// A smooth function whose zero set is the surface; f < 0 inside, f > 0 outside.
struct ImplicitFunction {
  std::function<double(const Vec3&)> value;
  std::function<Vec3(const Vec3&)> gradient;
};

/// The point Newton's iteration along the gradient, p ← p − f(p) ∇f(p) / |∇f(p)|², reaches
/// from p (at most 64 steps, stopping when |f|/|∇f| < 1e-15). Near the surface it is the
/// nearest surface point up to a relative error O((d κ)²) in the distance d (κ: curvature).
/// Throws Error when the gradient vanishes or the iteration does not settle.
Vec3 projectOntoZeroSet(const ImplicitFunction& f, const Vec3& p);

/// Marching tetrahedra of f over the box [lo, hi] in cubic cells of side
/// (hi − lo).maxCoeff() / cells, each cube split into the six tetrahedra around its main
/// diagonal (the Kuhn split, identical on shared faces, so the mesh is welded and closed when
/// f > 0 on the box's boundary). Triangles are oriented outward (towards f > 0) from the
/// tetrahedra's orientation alone, so the orientation is exact even on slivers. Grid values
/// closer to 0 than 5% of a cell (in units of |∇f|) are pushed away from 0 with their sign
/// kept, so no vertex lands on a grid point and no triangle collapses; every vertex is then
/// projected onto f = 0 (projectOntoZeroSet). The mesh has no normals.
TriangleMesh marchingTetrahedra(const ImplicitFunction& f, const Vec3& lo, const Vec3& hi,
                                int cells);

}  // namespace quadtri
