#include "quadtri/surface/shading_offset.h"

namespace quadtri {

Vec3 shadingOffsetPoint(const std::array<Vec3, 3>& v, const std::array<Vec3, 3>& n, const Vec3& b) {
  const Vec3 p = b[0] * v[0] + b[1] * v[1] + b[2] * v[2];
  const Vec3 cross = (v[1] - v[0]).cross(v[2] - v[0]);
  const double edges2 =
      (v[1] - v[0]).squaredNorm() + (v[2] - v[1]).squaredNorm() + (v[0] - v[2]).squaredNorm();
  // |cross| is twice the area; relative to the squared edges it is the sine of the angles.
  if (!(cross.squaredNorm() > 1e-24 * edges2 * edges2)) return p;
  Vec3 lift = Vec3::Zero(), normalSum = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    const double length = n[i].norm();
    if (!(length > 0.0) || !std::isfinite(length)) return p;
    const Vec3 unit = n[i] / length;
    normalSum += unit;
    // tᵢ = p − vᵢ; removing its negative normal component moves p' by bᵢ·max(0, −tᵢ·nᵢ)·nᵢ.
    const double height = (p - v[i]).dot(unit);
    if (height < 0.0) lift -= (b[i] * height) * unit;
  }
  const Vec3 lifted = p + lift;
  if (!allFinite(lifted)) return p;
  const double side = cross.dot(normalSum) >= 0.0 ? 1.0 : -1.0;
  if (side * cross.dot(lift) < 0.0) return p;
  return lifted;
}

Vec3 shadingOffsetPoint(const TriangleMesh& mesh, size_t t, const Vec3& b) {
  return shadingOffsetPoint(
      {mesh.corner(t, 0), mesh.corner(t, 1), mesh.corner(t, 2)},
      {mesh.cornerNormal(t, 0), mesh.cornerNormal(t, 1), mesh.cornerNormal(t, 2)}, b);
}

}  // namespace quadtri
