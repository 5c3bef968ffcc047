#include "quadtri/mesh/normals.h"

#include "quadtri/math/error.h"

namespace quadtri {

NormalSource parseNormalSource(std::string_view name) {
  if (name == "file") return NormalSource::File;
  if (name == "average") return NormalSource::Average;
  if (name == "angle") return NormalSource::Angle;
  fail("unknown normal source '{}': expected file, average or angle", name);
}

void computeVertexNormals(TriangleMesh& mesh, NormalSource source) {
  std::vector<Vec3> sum(mesh.positions.size(), Vec3::Zero());
  std::vector<Vec3> firstFace(mesh.positions.size(), Vec3::Zero());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 cross = mesh.faceCross(t);
    if (!(cross.norm() > 0.0)) continue;  // zero-area faces carry no direction
    const Vec3 n = cross.normalized();
    for (int k = 0; k < 3; ++k) {
      double w = 1.0;
      if (source == NormalSource::Angle) {
        const Vec3 e1 = mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k);
        const Vec3 e2 = mesh.corner(t, (k + 2) % 3) - mesh.corner(t, k);
        w = std::atan2(e1.cross(e2).norm(), e1.dot(e2));
      }
      const uint32_t v = mesh.triangles[t][k];
      sum[v] += w * n;
      if (firstFace[v].isZero()) firstFace[v] = n;
    }
  }
  mesh.normals.resize(mesh.positions.size());
  for (size_t v = 0; v < sum.size(); ++v)
    mesh.normals[v] = safeNormalized(sum[v], safeNormalized(firstFace[v]));
  mesh.normalIndices = mesh.triangles;
}

}  // namespace quadtri
