#include "quadtri/surface/implicit_model.h"

#include "quadtri/math/fixed_vector.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/implicit_fit.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"
#include "quadtri/surface/quadric_patch_parts.h"

namespace quadtri {
namespace {

// Lattice resolution (points per side minus one) of the samples that bound each patch.
constexpr int kBoundSamples = 4;
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

// f_p(u,v) projected along n, f_p's normal there (parametricNormal, which the caller has),
// onto q = 0, or nullopt where no root is within `reach` (longestEdge(fp), which the caller
// computes once per patch).
std::optional<Vec3> projectOntoQuadric(const QuadricCoeffs& q, const QuadraticPatch& fp,
                                       const Vec3& n, double u, double v, double reach) {
  const Vec3 p = fp.position(u, v);
  const auto s = nearestRayRoot(q, p, n, reach);
  if (!s) return std::nullopt;
  return Vec3(p + *s * n);
}

// projectOntoQuadric for the bounds, with the same root chosen, without normalising f_p's
// normal: along n = ∂u × ∂v the roots scale by |n| and the distance test compares squares, so
// neither the normal's nor the distance's square root is taken (nor the orientation, which only
// turns the line around). The point may differ from projectOntoQuadric's by rounding.
std::optional<Vec3> projectForBounds(const QuadricCoeffs& q, const QuadraticPatch& fp, double u,
                                     double v, double reach) {
  const Vec3 p = fp.position(u, v);
  Vec3 du, dv;
  fp.derivatives(u, v, du, dv);
  const Vec3 n = du.cross(dv);
  const double c = evalQuadric(q, p);
  if (c == 0.0) return p;
  const double nn = n.squaredNorm();
  if (!(nn > 0.0) || !std::isfinite(nn)) return std::nullopt;
  const double a = q[0] * n.x() * n.x() + q[1] * n.y() * n.y() + q[2] * n.z() * n.z() +
                   q[3] * n.x() * n.y() + q[4] * n.x() * n.z() + q[5] * n.y() * n.z();
  const double b = quadricGradient(q, p).dot(n);
  double roots[2];
  const int count = lineQuadricRoots(a, b, c, roots);
  const double reach2 = reach * reach;
  double best = 0.0;
  bool found = false;
  for (int i = 0; i < count; ++i) {
    const double s = roots[i];
    if (!std::isfinite(s) || s * s * nn > reach2) continue;
    if (!found || std::abs(s) < std::abs(best)) best = s;
    found = true;
  }
  if (!found) return std::nullopt;
  return Vec3(p + best * n);
}

}  // namespace

ImplicitModel::ImplicitModel(std::shared_ptr<const TriangleMesh> meshPtr, bool exactBoxes)
    : SurfaceModel(std::move(meshPtr)) {
  const TriangleMesh& m = mesh();
  const size_t n = m.triangleCount();
  // Where the control points follow from each triangle alone, none is kept and no adjacency is
  // built: parametricPatch computes them again when asked.
  const bool local = edgeControlPointsAreLocal(m);
  std::vector<uint8_t> fallbacks;
  if (local)
    fallbacks.assign(n, 0);
  else
    controlPoints_ = edgeControlPoints(m, &fallbacks);
  resizeLarge(patches_, n);
  parallelFor(size_t(0), n, [&](size_t t) {
    bool gaveUp = false;
    const QuadraticPatch fp = local
                                  ? QuadraticPatch{{m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)},
                                                   localEdgeControlPoints(m, t, &gaveUp)}
                                  : parametricPatch(t);
    if (gaveUp) fallbacks[t] = 1;
    const double orient = patchOrientation(m, t);
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
    const double reach = longestEdge(fp);
    // The samples on the quadric, which tell the exact box whether the quadric is well
    // conditioned where the patch is.
    FixedVector<Vec3, (kBoundSamples + 1) * (kBoundSamples + 2) / 2> onSurface;
    for (int i = 0; i <= kBoundSamples; ++i)
      for (int j = 0; i + j <= kBoundSamples; ++j) {
        const auto p = projectForBounds(patch.q, fp, double(i) / kBoundSamples,
                                        double(j) / kBoundSamples, reach);
        if (p) onSurface.push_back(*p);
        if (p && patch.inside(*p)) box.extend(*p);
      }
    box.inflate(kBoundMargin * reach);
    // The box above defines how far the patch reaches; its exact bounds within it are what
    // Embree is given, so that rays near a neighbour's surface do not test this patch too.
    patch.bounds = box;
    if (exactBoxes) patch.bounds = tightPatchBounds(patch, onSurface);
  });
  setFallbacks(std::move(fallbacks));
}

SurfacePoint ImplicitModel::evaluate(size_t t, double u, double v) const {
  return evaluateOn(parametricPatch(t), t, u, v);
}

void ImplicitModel::evaluateMany(size_t t, const Vec2* uv, size_t count, SurfacePoint* out) const {
  const QuadraticPatch fp = parametricPatch(t);
  for (size_t i = 0; i < count; ++i) out[i] = evaluateOn(fp, t, uv[i].x(), uv[i].y());
}

void ImplicitModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const QuadraticPatch fp = parametricPatch(t);
  for (size_t i = 0; i < count; ++i) out[i] = evaluateOn(fp, t, uv[i].x(), uv[i].y()).position;
}

SurfacePoint ImplicitModel::evaluateOn(const QuadraticPatch& fp, size_t t, double u,
                                       double v) const {
  const QuadricPatch& patch = patches_[t];
  const double orient = patchOrientation(mesh(), t);
  const Vec3 n = parametricNormal(fp, orient, u, v);
  // Where f_p is singular its normal falls back to the triangle's, oriented the same way.
  const Vec3 nParam = safeNormalized(n, orient * mesh().faceNormal(t));
  const auto p = projectOntoQuadric(patch.q, fp, n, u, v, longestEdge(fp));
  if (!p) return {fp.position(u, v), nParam};
  return {*p, safeNormalized(patch.orientation * quadricGradient(patch.q, *p), nParam)};
}

void ImplicitModel::patchRecord(size_t t, PatchRecord& out) const {
  addQuadraticPatch(parametricPatch(t), out);
  addQuadricPatch(patches_[t], out);
}

}  // namespace quadtri
