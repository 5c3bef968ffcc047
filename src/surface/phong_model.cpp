#include "quadtri/surface/phong_model.h"

#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"
#include "quadtri/surface/local_patches.h"

namespace quadtri {

PhongModel::PhongModel(std::shared_ptr<const TriangleMesh> mesh, double alpha)
    : SurfaceModel(std::move(mesh)), alpha_(alpha), sharesEdges_(edgesShareNormals(this->mesh())) {
  if (!std::isfinite(alpha)) fail("phong: shape factor α = {} is not finite", alpha);
}

SurfacePoint PhongModel::evaluate(size_t t, double u, double v) const {
  const LocalTriangle tri = localTriangle(mesh(), t);
  const double lambda[3] = {1.0 - u - v, u, v};
  // ∂λ_i/∂u and ∂λ_i/∂v.
  const double lu[3] = {-1.0, 1.0, 0.0};
  const double lv[3] = {-1.0, 0.0, 1.0};
  const Vec3 p = lambda[0] * tri.p[0] + lambda[1] * tri.p[1] + lambda[2] * tri.p[2];
  const Vec3 pu = tri.p[1] - tri.p[0];
  const Vec3 pv = tri.p[2] - tri.p[0];
  // p* = p − α Σ λ_i d_i n_i with d_i = (p − p_i)·n_i, the height above tangent plane i.
  Vec3 offset = Vec3::Zero(), du = Vec3::Zero(), dv = Vec3::Zero();
  for (int i = 0; i < 3; ++i) {
    const Vec3& n = tri.n[i];
    const double d = (p - tri.p[i]).dot(n);
    offset += lambda[i] * d * n;
    du += (lu[i] * d + lambda[i] * pu.dot(n)) * n;
    dv += (lv[i] * d + lambda[i] * pv.dot(n)) * n;
  }
  const Vec3 position = p - alpha_ * offset;
  const Vec3 tu = pu - alpha_ * du;
  const Vec3 tv = pv - alpha_ * dv;
  return {position, orientedPatchNormal(mesh(), t, u, v, tu, tv)};
}

nlohmann::json PhongModel::patchJson(size_t t) const {
  const LocalTriangle tri = localTriangle(mesh(), t);
  nlohmann::json j;
  j["alpha"] = alpha_;
  for (int k = 0; k < 3; ++k) {
    j["vertices"].push_back(vecJson(tri.p[k]));
    j["normals"].push_back(vecJson(tri.n[k]));
  }
  return j;
}

}  // namespace quadtri
