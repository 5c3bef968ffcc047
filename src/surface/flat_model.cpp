#include "quadtri/surface/flat_model.h"

#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {

std::string_view FlatModel::name() const {
  switch (normals_) {
    case Normals::Geometric:
      return "flat";
    case Normals::Interpolated:
      return "shading";
    case Normals::InterpolatedOffset:
      return "shading-offset";
  }
  return "flat";
}

SurfacePoint FlatModel::evaluate(size_t t, double u, double v) const {
  const TriangleMesh& m = mesh();
  const Vec3 p = (1.0 - u - v) * m.corner(t, 0) + u * m.corner(t, 1) + v * m.corner(t, 2);
  Vec3 n = m.faceNormal(t);
  // Orient to the shading normals' side so metrics compare like with like.
  const Vec3 ns = m.cornerNormal(t, 0) + m.cornerNormal(t, 1) + m.cornerNormal(t, 2);
  if (n.dot(ns) < 0.0) n = -n;
  return {p, n};
}

void FlatModel::patchRecord(size_t t, PatchRecord& out) const {
  addVertices(mesh(), t, out);
}

}  // namespace quadtri
