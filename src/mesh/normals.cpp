#include "quadtri/mesh/normals.h"

#include <cmath>
#include <numeric>

#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

// The corner angle of triangle t at corner k.
double cornerAngle(const TriangleMesh& mesh, size_t t, int k) {
  const Vec3 e1 = mesh.corner(t, (k + 1) % 3) - mesh.corner(t, k);
  const Vec3 e2 = mesh.corner(t, (k + 2) % 3) - mesh.corner(t, k);
  return std::atan2(e1.cross(e2).norm(), e1.dot(e2));
}

// Union-find over the mesh's corners (3t + k), smallest index as root so roots are
// deterministic.
struct CornerSets {
  std::vector<uint32_t> parent;
  explicit CornerSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
  uint32_t find(uint32_t c) {
    while (parent[c] != c) c = parent[c] = parent[parent[c]];
    return c;
  }
  void join(uint32_t a, uint32_t b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

}  // namespace

NormalSource parseNormalSource(std::string_view name) {
  if (name == "file") return NormalSource::File;
  if (name == "average") return NormalSource::Average;
  if (name == "angle") return NormalSource::Angle;
  fail("unknown normal source '{}': expected file, average or angle", name);
}

void checkCreaseAngle(double degrees) {
  if (!(degrees >= 0.0 && degrees <= 180.0))
    fail("--crease-angle {}: expected degrees from 0 to 180 (180: never split)", degrees);
}

void computeVertexNormals(TriangleMesh& mesh, NormalSource source) {
  std::vector<Vec3> sum = largeVector<Vec3>(mesh.positions.size(), Vec3::Zero());
  std::vector<Vec3> firstFace = largeVector<Vec3>(mesh.positions.size(), Vec3::Zero());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const Vec3 cross = mesh.faceCross(t);
    if (!(cross.norm() > 0.0)) continue;  // zero-area faces carry no direction
    const Vec3 n = cross.normalized();
    for (int k = 0; k < 3; ++k) {
      const double w = source == NormalSource::Angle ? cornerAngle(mesh, t, k) : 1.0;
      const uint32_t v = mesh.triangles[t][k];
      sum[v] += w * n;
      if (firstFace[v].isZero()) firstFace[v] = n;
    }
  }
  resizeLarge(mesh.normals, mesh.positions.size());
  for (size_t v = 0; v < sum.size(); ++v)
    mesh.normals[v] = safeNormalized(sum[v], safeNormalized(firstFace[v]));
  mesh.normalIndices = mesh.triangles;
}

void computeCreaseNormals(TriangleMesh& mesh, double creaseAngleDeg) {
  checkCreaseAngle(creaseAngleDeg);
  const size_t nt = mesh.triangleCount();
  std::vector<Vec3> faceNormal(nt, Vec3::Zero());
  std::vector<bool> hasArea(nt, false);
  for (size_t t = 0; t < nt; ++t) {
    const Vec3 cross = mesh.faceCross(t);
    hasArea[t] = cross.norm() > 0.0;
    if (hasArea[t]) faceNormal[t] = cross.normalized();
  }
  // Join the corners that two faces have at each end of an edge they share smoothly.
  const double crease = creaseAngleDeg * kPi / 180.0;
  const MeshTopology& topo = mesh.topology();
  CornerSets sets(3 * nt);
  for (const Edge& edge : topo.edges) {
    if (edge.sides.size() != 2) continue;  // boundary and non-manifold edges end a fan
    const auto [t0, k0] = edge.sides[0];
    const auto [t1, k1] = edge.sides[1];
    if (!hasArea[t0] || !hasArea[t1]) continue;
    const Vec3& n0 = faceNormal[t0];
    const Vec3& n1 = faceNormal[t1];
    if (creaseAngleDeg < 180.0 && std::atan2(n0.cross(n1).norm(), n0.dot(n1)) > crease) continue;
    // The corner of side (t, k) at position index v: corner k or k+1 of triangle t.
    auto cornerAt = [&](uint32_t t, uint8_t k, uint32_t v) {
      return 3 * t + (mesh.triangles[t][k] == v ? k : (k + 1) % 3);
    };
    for (const uint32_t v : {edge.a, edge.b}) sets.join(cornerAt(t0, k0, v), cornerAt(t1, k1, v));
  }
  // One normal per fan: the angle-weighted sum of its faces, summed in triangle order (the
  // order computeVertexNormals sums a vertex's faces in, so one fan gives the same bits).
  std::vector<uint32_t> fanOf(3 * nt, ~0u);
  std::vector<Vec3> sum;
  std::vector<uint32_t> fanVertex;
  for (uint32_t c = 0; c < 3 * nt; ++c) {
    const uint32_t root = sets.find(c);
    if (fanOf[root] == ~0u) {
      fanOf[root] = uint32_t(sum.size());
      sum.push_back(Vec3::Zero());
      fanVertex.push_back(mesh.triangles[c / 3][c % 3]);
    }
    fanOf[c] = fanOf[root];
  }
  for (size_t t = 0; t < nt; ++t) {
    if (!hasArea[t]) continue;
    for (int k = 0; k < 3; ++k) sum[fanOf[3 * t + k]] += cornerAngle(mesh, t, k) * faceNormal[t];
  }
  // Fallbacks: a fan whose sum vanishes (zero-area faces, a needle of opposite faces) gets the
  // vertex's unsplit angle-weighted normal, then its first face's normal.
  TriangleMesh unsplit;
  unsplit.positions = mesh.positions;
  unsplit.triangles = mesh.triangles;
  computeVertexNormals(unsplit, NormalSource::Angle);
  mesh.normals.resize(sum.size());
  for (size_t f = 0; f < sum.size(); ++f)
    mesh.normals[f] = safeNormalized(sum[f], unsplit.normals[fanVertex[f]]);
  mesh.normalIndices.resize(nt);
  for (size_t t = 0; t < nt; ++t)
    for (int k = 0; k < 3; ++k) mesh.normalIndices[t][k] = fanOf[3 * t + k];
}

void applyNormals(TriangleMesh& mesh, const NormalOptions& options) {
  switch (options.source) {
    case NormalSource::File:
      if (!mesh.hasNormals()) computeCreaseNormals(mesh, options.creaseAngleDeg);
      return;
    case NormalSource::Average:
      computeVertexNormals(mesh, NormalSource::Average);
      return;
    case NormalSource::Angle:
      computeCreaseNormals(mesh, options.creaseAngleDeg);
      return;
  }
}

}  // namespace quadtri
