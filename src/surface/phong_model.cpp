#include "quadtri/surface/phong_model.h"

#include <nlohmann/json.hpp>

#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/local_patches.h"

namespace quadtri {

PhongModel::PhongModel(std::shared_ptr<const TriangleMesh> mesh, double alpha)
    : QuadraticPatchModel(std::move(mesh)), alpha_(alpha) {
  if (!std::isfinite(alpha)) fail("phong: shape factor α = {} is not finite", alpha);
  const TriangleMesh& m = this->mesh();
  const EdgeEnds ends = edgeEnds(m);
  resizeLarge(controlPoints_, m.triangleCount());
  // Each triangle writes only its own points: the result does not depend on the thread count.
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
    const LocalTriangle tri = localTriangle(m, t);
    for (int i = 0; i < 3; ++i) {
      const int j = (i + 1) % 3;
      const Vec3 e = tri.p[j] - tri.p[i];
      // What projecting onto each end's tangent space removes from the chord: (e·n)n on a
      // tangent plane, e − (e·d)d on a crease line (the data both sides share there).
      const Vec3 removedI = e - ends[t][i][0].tangentPart(e, tri.n[i]);
      const Vec3 removedJ = e - ends[t][i][1].tangentPart(e, tri.n[j]);
      controlPoints_[t][i] = 0.5 * (tri.p[i] + tri.p[j]) - (0.5 * alpha_) * (removedI - removedJ);
    }
  });
}

nlohmann::json PhongModel::patchJson(size_t t) const {
  const LocalTriangle tri = localTriangle(mesh(), t);
  nlohmann::json j;
  j["alpha"] = alpha_;
  for (int k = 0; k < 3; ++k) {
    j["vertices"].push_back(vecJson(tri.p[k]));
    j["normals"].push_back(vecJson(tri.n[k]));
    j["control_points"].push_back(vecJson(controlPoints_[t][k]));
  }
  return j;
}

}  // namespace quadtri
