#include "quadtri/surface/local_patches.h"

#include <fmt/core.h>

#include <nlohmann/json.hpp>

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

LocalTriangle localTriangle(const TriangleMesh& mesh, size_t t) {
  LocalTriangle tri;
  for (int k = 0; k < 3; ++k) {
    tri.p[k] = mesh.corner(t, k);
    tri.n[k] = mesh.unitCornerNormal(t, k);
  }
  return tri;
}

Vec3 orientedPatchNormal(const TriangleMesh& mesh, size_t t, double u, double v, const Vec3& du,
                         const Vec3& dv) {
  const Vec3 cross = patchOrientation(mesh, t) * du.cross(dv);
  const double len = cross.norm();
  // Relative threshold: below it the cross product is round-off, not a direction.
  if (len > 1e-14 * du.norm() * dv.norm() && std::isfinite(len)) return cross / len;
  const Vec3 blend = (1.0 - u - v) * mesh.cornerNormal(t, 0) + u * mesh.cornerNormal(t, 1) +
                     v * mesh.cornerNormal(t, 2);
  return safeNormalized(blend, mesh.faceNormal(t));
}

nlohmann::json vecJson(const Vec3& v) {
  return {v.x(), v.y(), v.z()};
}

nlohmann::json quadraticPatchJson(const QuadraticPatch& p) {
  nlohmann::json j;
  for (const Vec3& corner : p.v) j["vertices"].push_back(vecJson(corner));
  j["control_points"] = {
      {"b01", vecJson(p.b[0])}, {"b12", vecJson(p.b[1])}, {"b20", vecJson(p.b[2])}};
  const std::array<Vec3, 6> c = p.coefficients();
  for (int k = 0; k < 6; ++k) j["coefficients"][fmt::format("c{}", k)] = vecJson(c[k]);
  return j;
}

nlohmann::json quadricPatchJson(const QuadricPatch& patch) {
  nlohmann::json j;
  j["quadric"] = patch.q;
  j["planes"] = nlohmann::json::array();
  for (int i = 0; i < patch.planeCount; ++i) {
    const Vec4& pl = patch.planes[i];
    j["planes"].push_back({pl[0], pl[1], pl[2], pl[3]});
  }
  j["bounds"] = {{"min", vecJson(patch.bounds.lo)}, {"max", vecJson(patch.bounds.hi)}};
  j["orientation"] = patch.orientation;
  return j;
}

}  // namespace quadtri
