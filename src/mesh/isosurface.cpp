#include "quadtri/mesh/isosurface.h"

#include <array>
#include <cmath>
#include <unordered_map>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

using Corner = std::array<int, 3>;

// Signed volume (×6) of the tetrahedron of four integer grid offsets: exact, so orientation
// decisions never depend on how thin a triangle is.
long orient(const Corner& a, const Corner& b, const Corner& c, const Corner& d) {
  const long u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const long v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const long w[3] = {d[0] - a[0], d[1] - a[1], d[2] - a[2]};
  return u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0]) +
         u[2] * (v[0] * w[1] - v[1] * w[0]);
}

}  // namespace

Vec3 projectOntoZeroSet(const ImplicitFunction& f, const Vec3& p) {
  Vec3 q = p;
  for (int step = 0; step < 64; ++step) {
    const double value = f.value(q);
    const Vec3 g = f.gradient(q);
    const double g2 = g.squaredNorm();
    if (!(g2 > 0.0) || !std::isfinite(g2))
      fail("projection onto f = 0 from ({}, {}, {}): the gradient vanishes at ({}, {}, {})", p.x(),
           p.y(), p.z(), q.x(), q.y(), q.z());
    if (std::abs(value) < 1e-15 * std::sqrt(g2)) return q;
    q -= value / g2 * g;
  }
  fail("projection onto f = 0 from ({}, {}, {}) did not converge in 64 Newton steps", p.x(), p.y(),
       p.z());
}

TriangleMesh marchingTetrahedra(const ImplicitFunction& f, const Vec3& lo, const Vec3& hi,
                                int cells) {
  if (cells < 1) fail("marching tetrahedra: expected at least 1 cell, got {}", cells);
  const Vec3 extent = hi - lo;
  if (!(extent.minCoeff() > 0.0))
    fail("marching tetrahedra: the box must have a positive extent on every axis");
  const double h = extent.maxCoeff() / cells;
  const int n[3] = {std::max(1, int(std::ceil(extent.x() / h - 1e-9))),
                    std::max(1, int(std::ceil(extent.y() / h - 1e-9))),
                    std::max(1, int(std::ceil(extent.z() / h - 1e-9)))};
  auto gridId = [&](int i, int j, int k) {
    return (uint64_t(k) * uint64_t(n[1] + 1) + uint64_t(j)) * uint64_t(n[0] + 1) + uint64_t(i);
  };
  auto gridPoint = [&](const Corner& c) { return Vec3(lo + h * Vec3(c[0], c[1], c[2])); };

  std::vector<double> values(size_t(n[0] + 1) * (n[1] + 1) * (n[2] + 1));
  for (int k = 0; k <= n[2]; ++k)
    for (int j = 0; j <= n[1]; ++j)
      for (int i = 0; i <= n[0]; ++i) {
        const Vec3 p = gridPoint({i, j, k});
        double value = f.value(p);
        const bool onBoundary = i == 0 || j == 0 || k == 0 || i == n[0] || j == n[1] || k == n[2];
        if (onBoundary && !(value > 0.0))
          fail(
              "marching tetrahedra: f = {} at the box boundary point ({}, {}, {}), expected > 0 "
              "(the surface must lie inside the box)",
              value, p.x(), p.y(), p.z());
        const double margin = 0.05 * h * f.gradient(p).norm();
        if (std::abs(value) < margin) value = value < 0.0 ? -margin : margin;
        values[gridId(i, j, k)] = value;
      }

  TriangleMesh mesh;
  std::unordered_map<uint64_t, uint32_t> edgeVertex;
  const uint64_t gridCount = values.size();
  // The surface vertex on the grid edge (a, b), shared by every tetrahedron that uses the edge.
  auto vertexOn = [&](const Corner& a, const Corner& b) {
    uint64_t ia = gridId(a[0], a[1], a[2]), ib = gridId(b[0], b[1], b[2]);
    const Vec3 pa = gridPoint(a), pb = gridPoint(b);
    const double fa = values[ia], fb = values[ib];
    if (ia > ib) std::swap(ia, ib);
    const auto [it, inserted] = edgeVertex.emplace(ia * gridCount + ib, 0);
    if (inserted) {
      const double t = fa / (fa - fb);
      mesh.positions.push_back(projectOntoZeroSet(f, pa + t * (pb - pa)));
      it->second = uint32_t(mesh.positions.size() - 1);
    }
    return it->second;
  };
  auto addQuad = [&](uint32_t q0, uint32_t q1, uint32_t q2, uint32_t q3) {
    const auto& P = mesh.positions;
    if ((P[q0] - P[q2]).squaredNorm() <= (P[q1] - P[q3]).squaredNorm()) {
      mesh.triangles.push_back({q0, q1, q2});
      mesh.triangles.push_back({q0, q2, q3});
    } else {
      mesh.triangles.push_back({q0, q1, q3});
      mesh.triangles.push_back({q1, q2, q3});
    }
  };

  const int permutations[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i)
        for (const auto& perm : permutations) {
          // The path 0 → e_a → e_a + e_b → (1,1,1) through the cube.
          std::array<Corner, 4> v;
          v[0] = {i, j, k};
          v[1] = v[0];
          v[1][perm[0]] += 1;
          v[2] = v[1];
          v[2][perm[1]] += 1;
          v[3] = {i + 1, j + 1, k + 1};
          std::vector<int> inside, outside;
          for (int c = 0; c < 4; ++c)
            (values[gridId(v[c][0], v[c][1], v[c][2])] < 0.0 ? inside : outside).push_back(c);
          if (inside.empty() || outside.empty()) continue;
          if (inside.size() == 2) {
            const Corner &i0 = v[inside[0]], &i1 = v[inside[1]];
            const Corner &o0 = v[outside[0]], &o1 = v[outside[1]];
            // (i0o0, i0o1, i1o1, i1o0) faces the outside exactly when (i0, i1, o0, o1) is
            // positively oriented.
            const uint32_t q[4] = {vertexOn(i0, o0), vertexOn(i0, o1), vertexOn(i1, o1),
                                   vertexOn(i1, o0)};
            if (orient(i0, i1, o0, o1) > 0)
              addQuad(q[0], q[1], q[2], q[3]);
            else
              addQuad(q[3], q[2], q[1], q[0]);
            continue;
          }
          // One vertex s alone on its side: the triangle cuts its three edges and, when
          // (s, a, b, c) is positively oriented, faces away from s.
          const bool loneInside = inside.size() == 1;
          const int s = loneInside ? inside[0] : outside[0];
          const std::vector<int>& others = loneInside ? outside : inside;
          const Corner &a = v[others[0]], &b = v[others[1]], &c = v[others[2]];
          const uint32_t ta = vertexOn(v[s], a), tb = vertexOn(v[s], b), tc = vertexOn(v[s], c);
          if ((orient(v[s], a, b, c) > 0) == loneInside)
            mesh.triangles.push_back({ta, tb, tc});
          else
            mesh.triangles.push_back({ta, tc, tb});
        }
  if (mesh.triangles.empty())
    fail("marching tetrahedra: f has no zero crossing on the {}x{}x{} grid", n[0], n[1], n[2]);
  return mesh;
}

}  // namespace quadtri
