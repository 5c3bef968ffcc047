#include "quadtri/mesh/triangle_mesh.h"

#include "quadtri/math/error.h"

namespace quadtri {

Vec3 TriangleMesh::faceCross(size_t t) const {
  const Vec3& a = corner(t, 0);
  return (corner(t, 1) - a).cross(corner(t, 2) - a);
}

Vec3 TriangleMesh::faceNormal(size_t t) const {
  return safeNormalized(faceCross(t));
}

Vec3 TriangleMesh::cornerNormal(size_t t, int k) const {
  if (normalIndices.empty()) return faceNormal(t);
  return normals[normalIndices[t][k]];
}

Vec3 TriangleMesh::unitCornerNormal(size_t t, int k) const {
  const Vec3 unit = safeNormalized(cornerNormal(t, k), Vec3::Zero());
  return unit != Vec3::Zero() ? unit : faceNormal(t);
}

Bounds3 TriangleMesh::bounds() const {
  Bounds3 b;
  for (const Vec3& p : positions) b.extend(p);
  return b;
}

double TriangleMesh::meanEdgeLength(size_t t) const {
  return ((corner(t, 1) - corner(t, 0)).norm() + (corner(t, 2) - corner(t, 1)).norm() +
          (corner(t, 0) - corner(t, 2)).norm()) /
         3.0;
}

double TriangleMesh::meanEdgeLength() const {
  if (triangles.empty()) return 0.0;
  double sum = 0.0;
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) sum += (corner(t, (k + 1) % 3) - corner(t, k)).norm();
  return sum / (3.0 * triangles.size());
}

void TriangleMesh::validate(const std::string& what) const {
  for (size_t i = 0; i < positions.size(); ++i)
    if (!allFinite(positions[i])) fail("{}: vertex {} has a non-finite coordinate", what, i);
  for (size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles[t][k] >= positions.size())
        fail("{}: triangle {} corner {} indexes vertex {}, but there are only {} vertices", what, t,
             k, triangles[t][k], positions.size());
  if (normalIndices.empty()) return;
  if (normalIndices.size() != triangles.size())
    fail("{}: {} normal index triples for {} triangles", what, normalIndices.size(),
         triangles.size());
  for (size_t i = 0; i < normals.size(); ++i)
    if (!allFinite(normals[i]) || std::abs(normals[i].norm() - 1.0) > 1e-6)
      fail("{}: normal {} is not a finite unit vector", what, i);
  for (size_t t = 0; t < normalIndices.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (normalIndices[t][k] >= normals.size())
        fail("{}: triangle {} corner {} indexes normal {}, but there are only {} normals", what, t,
             k, normalIndices[t][k], normals.size());
}

}  // namespace quadtri
