#include "quadtri/surface/nagata_model.h"

#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {
namespace {

// (1 − cos 0.1°)/2: Δc (and 1 − Δc) below this count as parallel (opposite) normals.
const double kParallelDeltaC = 0.5 * (1.0 - std::cos(0.1 * kPi / 180.0));
// sin 0.1°: a straight edge whose chord leaves a tangent plane by more than this (relative to
// its length) is not tangent there.
const double kTangentTolerance = std::sin(0.1 * kPi / 180.0);

}  // namespace

Vec3 nagataCurvature(const Vec3& x0In, const Vec3& n0In, const Vec3& x1In, const Vec3& n1In,
                     bool* gaveUp) {
  if (gaveUp) *gaveUp = false;
  // The formula is symmetric; a canonical order makes both sides of an edge agree bit for bit.
  const bool swap = edgeEndsSwapped(x0In, n0In, x1In, n1In);
  const Vec3& x0 = swap ? x1In : x0In;
  const Vec3& x1 = swap ? x0In : x1In;
  const Vec3& n0 = swap ? n1In : n0In;
  const Vec3& n1 = swap ? n0In : n1In;
  const Vec3 dx = x1 - x0;
  const Vec3 v = 0.5 * (n0 + n1);
  const Vec3 dv = 0.5 * (n0 - n1);
  // For unit normals Δc = n0·Δv = |Δv|² and 1 − Δc = |v|²; the squared norms avoid the
  // cancellation in 1 − n0·n1 when the normals are close.
  const double deltaC = dv.squaredNorm();
  const double oneMinusDeltaC = v.squaredNorm();
  if (deltaC <= kParallelDeltaC || oneMinusDeltaC <= kParallelDeltaC) {
    if (gaveUp)
      *gaveUp =
          std::max(std::abs(n0.dot(dx)), std::abs(n1.dot(dx))) > kTangentTolerance * dx.norm();
    return Vec3::Zero();
  }
  return (dx.dot(dv) / oneMinusDeltaC) * v + (dx.dot(v) / deltaC) * dv;
}

NagataModel::NagataModel(std::shared_ptr<const TriangleMesh> mesh)
    : QuadraticPatchModel(std::move(mesh)) {
  const TriangleMesh& m = this->mesh();
  const EdgeEnds ends = edgeEnds(m);
  // A smooth mesh keeps nothing (computeControlPoints, curvature); its fallbacks are counted.
  const bool keep = edgeEndsNeedTopology(m);
  if (keep) {
    resizeLarge(curvatures_, m.triangleCount());
    resizeLarge(controlPoints_, m.triangleCount());
  }
  std::vector<uint8_t> gaveUp(m.triangleCount(), 0);
  // Each triangle writes only its own slots: the result does not depend on the thread count.
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
    const LocalTriangle tri = localTriangle(m, t);
    for (int k = 0; k < 3; ++k) {
      const int l = (k + 1) % 3;
      const auto& [ek, el] = ends[t][k];
      if (ek.crease() || el.crease()) {
        // At a crease the tangent follows the crease line both sides share (creases.h): only
        // where normals split, so on a mesh that keeps its points.
        const Vec3 b = creaseControlPoint(tri.p[k], ek, tri.n[k], tri.p[l], el, tri.n[l]);
        controlPoints_[t][k] = b;
        curvatures_[t][k] = tri.p[k] + tri.p[l] - 2.0 * b;
        continue;
      }
      bool straight = false;
      const Vec3 c = nagataCurvature(tri.p[k], ek.normalFor(tri.n[k]), tri.p[l],
                                     el.normalFor(tri.n[l]), &straight);
      gaveUp[t] |= straight;
      if (!keep) continue;
      curvatures_[t][k] = c;
      // x(t) = x0 + (Δx − c) t + c t² in Bernstein form: control point x0 + (Δx − c)/2.
      controlPoints_[t][k] = 0.5 * (tri.p[k] + tri.p[l]) - 0.5 * c;
    }
  });
  setFallbacks(std::move(gaveUp));
}

std::array<Vec3, 3> NagataModel::computeControlPoints(size_t t) const {
  const TriangleMesh& m = mesh();
  std::array<Vec3, 3> b;
  for (int k = 0; k < 3; ++k) {
    const int l = (k + 1) % 3;
    b[k] = 0.5 * (m.corner(t, k) + m.corner(t, l)) - 0.5 * curvature(t, k);
  }
  return b;
}

Vec3 NagataModel::curvature(size_t t, int k) const {
  if (!curvatures_.empty()) return curvatures_[t][k];
  // Every end Shared: each side's normal is its own, as the constructor passed them.
  const TriangleMesh& m = mesh();
  const int l = (k + 1) % 3;
  return nagataCurvature(m.corner(t, k), m.unitCornerNormal(t, k), m.corner(t, l),
                         m.unitCornerNormal(t, l));
}

void NagataModel::patchRecord(size_t t, PatchRecord& out) const {
  const QuadraticPatch patch = this->patch(t);
  const PatchRecord::Ref vertices = out.setArray(PatchRecord::kRoot, "vertices");
  const PatchRecord::Ref curvature = out.setArray(PatchRecord::kRoot, "curvature");
  const PatchRecord::Ref control = out.setArray(PatchRecord::kRoot, "control_points");
  for (int k = 0; k < 3; ++k) {
    out.push(vertices, patch.v[k]);
    out.push(curvature, this->curvature(t, k));
    out.push(control, patch.b[k]);
  }
}

}  // namespace quadtri
