#include "quadtri/surface/phong_model.h"

#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {

namespace {

// b_ij = (p_i + p_j)/2 − (α/2)(R_i(e) − R_j(e)) for each edge of `tri` with its ends `ends`.
std::array<Vec3, 3> phongControlPoints(const LocalTriangle& tri, const EdgeEnds::Triangle& ends,
                                       double alpha) {
  std::array<Vec3, 3> b;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const Vec3 e = tri.p[j] - tri.p[i];
    // What projecting onto each end's tangent space removes from the chord: (e·n)n on a
    // tangent plane, e − (e·d)d on a crease line (the data both sides share there).
    const Vec3 removedI = e - ends[i][0].tangentPart(e, tri.n[i]);
    const Vec3 removedJ = e - ends[i][1].tangentPart(e, tri.n[j]);
    b[i] = 0.5 * (tri.p[i] + tri.p[j]) - (0.5 * alpha) * (removedI - removedJ);
  }
  return b;
}

}  // namespace

PhongModel::PhongModel(std::shared_ptr<const TriangleMesh> mesh, double alpha)
    : QuadraticPatchModel(std::move(mesh)), alpha_(alpha) {
  if (!std::isfinite(alpha)) fail("phong: shape factor α = {} is not finite", alpha);
  const TriangleMesh& m = this->mesh();
  if (!edgeEndsNeedTopology(m)) return;  // every end Shared: computeControlPoints
  const EdgeEnds ends = edgeEnds(m);
  resizeLarge(controlPoints_, m.triangleCount());
  // Each triangle writes only its own points: the result does not depend on the thread count.
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
    controlPoints_[t] = phongControlPoints(localTriangle(m, t), ends[t], alpha_);
  });
}

std::array<Vec3, 3> PhongModel::computeControlPoints(size_t t) const {
  return phongControlPoints(localTriangle(mesh(), t), EdgeEnds::Triangle{}, alpha_);
}

void PhongModel::patchRecord(size_t t, PatchRecord& out) const {
  const LocalTriangle tri = localTriangle(mesh(), t);
  out.set(PatchRecord::kRoot, "alpha", alpha_);
  const std::array<Vec3, 3> b = controlPoints(t);
  const PatchRecord::Ref vertices = out.setArray(PatchRecord::kRoot, "vertices");
  const PatchRecord::Ref normals = out.setArray(PatchRecord::kRoot, "normals");
  const PatchRecord::Ref control = out.setArray(PatchRecord::kRoot, "control_points");
  for (int k = 0; k < 3; ++k) {
    out.push(vertices, tri.p[k]);
    out.push(normals, tri.n[k]);
    out.push(control, b[k]);
  }
}

}  // namespace quadtri
