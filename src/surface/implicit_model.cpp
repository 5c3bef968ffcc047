#include "surface/implicit_model.h"

#include <nlohmann/json.hpp>

#include "surface/implicit_fit.h"

namespace quadtri {
namespace {

// Lattice resolution (points per side minus one) of the samples that bound each patch.
constexpr int kBoundSamples = 8;
// Bounds margin, as a fraction of the triangle's longest edge.
constexpr double kBoundMargin = 0.05;

double longestEdge(const QuadraticPatch& fp) {
  return std::max(
      {(fp.v[1] - fp.v[0]).norm(), (fp.v[2] - fp.v[1]).norm(), (fp.v[0] - fp.v[2]).norm()});
}

// Unit normal of f_p at (u,v), oriented by `orientation`; zero where f_p is singular.
Vec3 parametricNormal(const QuadraticPatch& fp, double orientation, double u, double v) {
  Vec3 du, dv;
  fp.derivatives(u, v, du, dv);
  return orientation * safeNormalized(du.cross(dv), Vec3::Zero());
}

// f_p(u,v) projected along f_p's normal onto q = 0, or nullopt where no root is near.
std::optional<Vec3> projectOntoQuadric(const QuadricCoeffs& q, const QuadraticPatch& fp,
                                       double orientation, double u, double v) {
  const Vec3 p = fp.position(u, v);
  const Vec3 n = parametricNormal(fp, orientation, u, v);
  const auto s = nearestRayRoot(q, p, n, longestEdge(fp));
  if (!s) return std::nullopt;
  return Vec3(p + *s * n);
}

nlohmann::json toJson(const Vec3& p) {
  return {p.x(), p.y(), p.z()};
}

}  // namespace

ImplicitModel::ImplicitModel(std::shared_ptr<const TriangleMesh> meshPtr)
    : SurfaceModel(std::move(meshPtr)) {
  const TriangleMesh& m = mesh();
  const auto controlPoints = edgeControlPoints(m);
  const size_t n = m.triangleCount();
  parametric_.reserve(n);
  parametricOrientation_.reserve(n);
  patches_.resize(n);
  for (size_t t = 0; t < n; ++t) {
    const QuadraticPatch fp = quadraticPatch(m, controlPoints, t);
    const double orient = patchOrientation(m, t);
    parametric_.push_back(fp);
    parametricOrientation_.push_back(orient);
    QuadricPatch& patch = patches_[t];
    patch.q = fitThesisQuadric(fp);
    setThesisClipPlanes(fp, patch);

    // Orientation: the gradient's agreement with the shading normals at the corners and with
    // f_p's normal at the barycentre.
    const double third = 1.0 / 3.0;
    double agreement = quadricGradient(patch.q, fp.position(third, third))
                           .dot(parametricNormal(fp, orient, third, third));
    for (int k = 0; k < 3; ++k)
      agreement += quadricGradient(patch.q, m.corner(t, k)).dot(m.cornerNormal(t, k));
    patch.orientation = agreement < 0.0 ? -1.0 : 1.0;

    Bounds3 box;
    for (int k = 0; k < 3; ++k) box.extend(m.corner(t, k));
    for (int i = 0; i <= kBoundSamples; ++i)
      for (int j = 0; i + j <= kBoundSamples; ++j) {
        const auto p = projectOntoQuadric(patch.q, fp, orient, double(i) / kBoundSamples,
                                          double(j) / kBoundSamples);
        if (p && patch.inside(*p)) box.extend(*p);
      }
    box.inflate(kBoundMargin * longestEdge(fp));
    patch.bounds = box;
  }
}

SurfacePoint ImplicitModel::evaluate(size_t t, double u, double v) const {
  const QuadraticPatch& fp = parametric_[t];
  const QuadricPatch& patch = patches_[t];
  const double orient = parametricOrientation_[t];
  // Where f_p is singular its normal falls back to the triangle's, oriented the same way.
  const Vec3 nParam =
      safeNormalized(parametricNormal(fp, orient, u, v), orient * mesh().faceNormal(t));
  const auto p = projectOntoQuadric(patch.q, fp, orient, u, v);
  if (!p) return {fp.position(u, v), nParam};
  return {*p, safeNormalized(patch.orientation * quadricGradient(patch.q, *p), nParam)};
}

nlohmann::json ImplicitModel::patchJson(size_t t) const {
  const QuadricPatch& patch = patches_[t];
  nlohmann::json j;
  j["quadric"] = patch.q;
  j["planes"] = nlohmann::json::array();
  for (int i = 0; i < patch.planeCount; ++i) {
    const Vec4& pl = patch.planes[i];
    j["planes"].push_back({pl[0], pl[1], pl[2], pl[3]});
  }
  j["bounds"] = {{"min", toJson(patch.bounds.lo)}, {"max", toJson(patch.bounds.hi)}};
  nlohmann::json c = nlohmann::json::array();
  for (const Vec3& ci : parametric_[t].coefficients()) c.push_back(toJson(ci));
  j["parametric"] = {{"c", c}};
  j["control_points"] = nlohmann::json::array();
  for (const Vec3& b : parametric_[t].b) j["control_points"].push_back(toJson(b));
  return j;
}

}  // namespace quadtri
