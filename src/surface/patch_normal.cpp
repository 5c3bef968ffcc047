#include "surface/patch_normal.h"

#include "surface/edge_curves.h"

namespace quadtri {
namespace {

// Below this |p_u × p_v| / (|p_u||p_v|) (sine of the angle between the tangents) the cross
// product's direction is rounding noise.
constexpr double kMinTangentSine = 1e-12;

}  // namespace

Vec3 orientedPatchNormal(const TriangleMesh& mesh, size_t t, double u, double v, const Vec3& pu,
                         const Vec3& pv) {
  const Vec3 n = pu.cross(pv);
  const double len = n.norm();
  if (std::isfinite(len) && len > kMinTangentSine * pu.norm() * pv.norm())
    return (patchOrientation(mesh, t) / len) * n;
  Vec3 face = mesh.faceNormal(t);
  const Vec3 mix = (1.0 - u - v) * mesh.cornerNormal(t, 0) + u * mesh.cornerNormal(t, 1) +
                   v * mesh.cornerNormal(t, 2);
  if (face.dot(mix) < 0.0) face = -face;
  return safeNormalized(mix, face);
}

}  // namespace quadtri
