#include "quadtri/surface/local_patches.h"

#include "quadtri/surface/edge_curves.h"
#include "quadtri/surface/patch_record.h"
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

void addControlNet(const QuadraticPatch& p, PatchRecord& out) {
  const PatchRecord::Ref vertices = out.setArray(PatchRecord::kRoot, "vertices");
  for (const Vec3& corner : p.v) out.push(vertices, corner);
  const PatchRecord::Ref control = out.setObject(PatchRecord::kRoot, "control_points");
  out.set(control, "b01", p.b[0]);
  out.set(control, "b12", p.b[1]);
  out.set(control, "b20", p.b[2]);
}

void addQuadraticPatch(const QuadraticPatch& p, PatchRecord& out) {
  addControlNet(p, out);
  const std::array<Vec3, 6> c = p.coefficients();
  const PatchRecord::Ref coefficients = out.setObject(PatchRecord::kRoot, "coefficients");
  constexpr const char* kNames[6] = {"c0", "c1", "c2", "c3", "c4", "c5"};
  for (int k = 0; k < 6; ++k) out.set(coefficients, kNames[k], c[k]);
}

void addQuadricPatch(const QuadricPatch& patch, PatchRecord& out) {
  const PatchRecord::Ref root = PatchRecord::kRoot;
  out.set(root, "quadric", patch.q.data(), patch.q.size());
  const PatchRecord::Ref planes = out.setArray(root, "planes");
  for (int i = 0; i < patch.planeCount; ++i) out.push(planes, patch.planes[i].data(), 4);
  const PatchRecord::Ref bounds = out.setObject(root, "bounds");
  out.set(bounds, "min", patch.bounds.lo);
  out.set(bounds, "max", patch.bounds.hi);
  out.set(root, "orientation", double(patch.orientation));
}

void addVertices(const TriangleMesh& mesh, size_t t, PatchRecord& out) {
  const PatchRecord::Ref vertices = out.setArray(PatchRecord::kRoot, "vertices");
  for (int k = 0; k < 3; ++k) out.push(vertices, mesh.corner(t, k));
}

}  // namespace quadtri
