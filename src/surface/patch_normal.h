// The oriented unit normal of a parametric patch, with a defined value where it degenerates.
#pragma once

#include "mesh/triangle_mesh.h"

namespace quadtri {

/// Unit normal (p_u × p_v)/|p_u × p_v| of patch t at barycentric (u, v), turned by
/// patchOrientation to the side of the shading normals. Where the cross product vanishes
/// relative to |p_u||p_v| (a zero-area triangle, a cusp) it falls back to the normalised
/// barycentric mix of the corner normals, then to the oriented face normal: never NaN.
Vec3 orientedPatchNormal(const TriangleMesh& mesh, size_t t, double u, double v, const Vec3& pu,
                         const Vec3& pv);

}  // namespace quadtri
