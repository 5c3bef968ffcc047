#include "quadtri/surface/pn_model.h"

#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/local_patches.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {
namespace {

// Index (i, j, k) with i + j + k = 3 of the edge point next to corner a towards corner b.
std::array<int, 3> edgeIndex(int a, int b) {
  std::array<int, 3> e = {0, 0, 0};
  e[a] = 2;
  e[b] = 1;
  return e;
}

}  // namespace

PnPatch PnPatch::fromCorners(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& nrm,
                             const std::array<std::array<EdgeEnd, 2>, 3>* ends) {
  PnPatch patch = fromEdgePoints(p, cornerEdgePoints(p, nrm, ends));
  patch.setNormalField(p, nrm);
  return patch;
}

std::array<Vec3, 6> PnPatch::cornerEdgePoints(const std::array<Vec3, 3>& p,
                                              const std::array<Vec3, 3>& nrm,
                                              const std::array<std::array<EdgeEnd, 2>, 3>* ends) {
  std::array<Vec3, 6> edgePoints;
  int next = 0;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      // The end of edge ab at a: local edge a (a → a+1) starts there, edge b (b → a) ends there.
      const EdgeEnd* end = nullptr;
      if (ends) end = b == (a + 1) % 3 ? &(*ends)[a][0] : &(*ends)[b][1];
      if (end && end->crease()) {
        // At a crease: (2p_a + p_b)/3 projected onto the crease line through p_a, which both
        // sides of the edge share (creases.h).
        edgePoints[next++] = p[a] + end->tangentPart(p[b] - p[a], nrm[a]) / 3.0;
      } else {
        // Subtracting w_ab n_a, w_ab = (p_b − p_a)·n_a, projects (2p_a + p_b)/3 onto a's
        // tangent plane.
        const Vec3& n = end ? end->normalFor(nrm[a]) : nrm[a];
        const double w = (p[b] - p[a]).dot(n);
        edgePoints[next++] = (2.0 * p[a] + p[b] - w * n) / 3.0;
      }
    }
  return edgePoints;
}

PnPatch PnPatch::fromEdgePoints(const std::array<Vec3, 3>& p,
                                const std::array<Vec3, 6>& edgePoints) {
  PnPatch patch;
  auto at = [&](const std::array<int, 3>& e) -> Vec3& { return patch.b[e[0]][e[1]]; };
  Vec3 edgeSum = Vec3::Zero();
  int next = 0;
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> c = {0, 0, 0};
    c[a] = 3;
    at(c) = p[a];
    for (int b = 0; b < 3; ++b) {
      if (b == a) continue;
      at(edgeIndex(a, b)) = edgePoints[next];
      edgeSum += edgePoints[next++];
    }
  }
  const Vec3 e = edgeSum / 6.0;
  const Vec3 centroid = (p[0] + p[1] + p[2]) / 3.0;
  patch.b[1][1] = e + 0.5 * (e - centroid);
  return patch;
}

void PnPatch::setNormalField(const std::array<Vec3, 3>& p, const std::array<Vec3, 3>& nrm) {
  for (int a = 0; a < 3; ++a) {
    std::array<int, 3> c = {0, 0, 0};
    c[a] = 2;
    n[c[0]][c[1]] = nrm[a];
    const int next = (a + 1) % 3;
    const Vec3 edge = p[next] - p[a];
    const double len2 = edge.squaredNorm();
    const Vec3 sum = nrm[a] + nrm[next];
    // A zero-length edge has no mirror plane: keep the plain sum there.
    const double vab = len2 > 0.0 ? 2.0 * edge.dot(sum) / len2 : 0.0;
    std::array<int, 3> m = {0, 0, 0};
    m[a] = 1;
    m[next] = 1;
    // Opposite normals across the edge make h vanish: that term then drops out of the field.
    n[m[0]][m[1]] = safeNormalized(sum - vab * edge, Vec3::Zero());
  }
}

std::array<Vec3, 6> PnPatch::edgePoints() const {
  std::array<Vec3, 6> out;
  int next = 0;
  for (int a = 0; a < 3; ++a)
    for (int other = 0; other < 3; ++other)
      if (other != a) {
        const std::array<int, 3> e = edgeIndex(a, other);
        out[next++] = b[e[0]][e[1]];
      }
  return out;
}

namespace {

// Powers 0 to 3 of the barycentric coordinates (1 - u - v, u, v): power[c][e] = l_c^e, by
// multiplication (std::pow took most of a tessellation's time).
struct BarycentricPowers {
  double power[3][4];
  BarycentricPowers(double u, double v) {
    const double l[3] = {1.0 - u - v, u, v};
    for (int c = 0; c < 3; ++c) {
      power[c][0] = 1.0;
      power[c][1] = l[c];
      power[c][2] = l[c] * l[c];
      power[c][3] = power[c][2] * l[c];
    }
  }
  double operator()(int i, int j, int k) const { return power[0][i] * power[1][j] * power[2][k]; }
};

}  // namespace

Vec3 PnPatch::position(double u, double v) const {
  const BarycentricPowers l(u, v);
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) {
      const int k = 3 - i - j;
      // Multinomial 3!/(i!j!k!): 1 at corners, 3 on edges, 6 at the centre.
      const double m = (i == 3 || j == 3 || k == 3) ? 1.0 : (i == 1 && j == 1) ? 6.0 : 3.0;
      sum += m * l(i, j, k) * b[i][j];
    }
  return sum;
}

void PnPatch::derivatives(double u, double v, Vec3& du, Vec3& dv) const {
  const BarycentricPowers l(u, v);
  du = Vec3::Zero();
  dv = Vec3::Zero();
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; i + j <= 2; ++j) {
      const int k = 2 - i - j;
      // Quadratic Bernstein 2!/(i!j!k!): 1 at corners, 2 on edges.
      const double m = (i == 2 || j == 2 || k == 2) ? 1.0 : 2.0;
      const double basis = m * l(i, j, k);
      du += basis * (b[i][j + 1] - b[i + 1][j]);
      dv += basis * (b[i][j] - b[i + 1][j]);  // b_{i,j,k+1} − b_{i+1,j,k}
    }
  du *= 3.0;
  dv *= 3.0;
}

Vec3 PnPatch::normalField(double u, double v) const {
  const BarycentricPowers l(u, v);
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; i + j <= 2; ++j) sum += l(i, j, 2 - i - j) * n[i][j];
  return sum;
}

PnModel::PnModel(std::shared_ptr<const TriangleMesh> mesh) : SurfaceModel(std::move(mesh)) {
  const TriangleMesh& m = this->mesh();
  // Every end Shared: the points are the ones cornerEdgePoints gives without ends, bit for bit
  // (a Shared end's normal is the corner's own).
  if (!edgeEndsNeedTopology(m)) return;
  const EdgeEnds ends = edgeEnds(m);
  resizeLarge(edgePoints_, m.triangleCount());
  // Each triangle writes only its own points: the result does not depend on the thread count.
  parallelFor(size_t(0), m.triangleCount(), [&](size_t t) {
    const LocalTriangle tri = localTriangle(m, t);
    edgePoints_[t] = PnPatch::cornerEdgePoints(tri.p, tri.n, &ends[t]);
  });
}

std::array<Vec3, 6> PnModel::edgePoints(size_t t, const std::array<Vec3, 3>& p) const {
  if (!edgePoints_.empty()) return edgePoints_[t];
  const TriangleMesh& m = mesh();
  return PnPatch::cornerEdgePoints(
      p, {m.unitCornerNormal(t, 0), m.unitCornerNormal(t, 1), m.unitCornerNormal(t, 2)});
}

PnPatch PnModel::geometry(size_t t) const {
  const TriangleMesh& m = mesh();
  const std::array<Vec3, 3> p = {m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)};
  return PnPatch::fromEdgePoints(p, edgePoints(t, p));
}

PnPatch PnModel::patch(size_t t) const {
  const LocalTriangle tri = localTriangle(mesh(), t);
  PnPatch patch = PnPatch::fromEdgePoints(tri.p, edgePoints(t, tri.p));
  patch.setNormalField(tri.p, tri.n);
  return patch;
}

SurfacePoint PnModel::evaluate(size_t t, double u, double v) const {
  const PnPatch patch = geometry(t);
  Vec3 du, dv;
  patch.derivatives(u, v, du, dv);
  return {patch.position(u, v), orientedPatchNormal(mesh(), t, u, v, du, dv)};
}

Vec3 PnModel::position(size_t t, double u, double v) const {
  return geometry(t).position(u, v);
}

void PnModel::positions(size_t t, const Vec2* uv, size_t count, Vec3* out) const {
  const PnPatch patch = geometry(t);
  for (size_t i = 0; i < count; ++i) out[i] = patch.position(uv[i].x(), uv[i].y());
}

Vec3 PnModel::pnNormal(size_t t, double u, double v) const {
  const Vec3 field = patch(t).normalField(u, v);
  const double len = field.norm();
  if (len > 1e-12 && std::isfinite(len)) return field / len;
  return evaluate(t, u, v).normal;
}

void PnModel::patchRecord(size_t t, PatchRecord& out) const {
  const PnPatch patch = this->patch(t);
  addVertices(mesh(), t, out);
  // Keys bIJK and nIJK: the control point's (or normal coefficient's) Bernstein indices.
  const auto name = [](char letter, int i, int j, int k) {
    return std::string{letter, char('0' + i), char('0' + j), char('0' + k)};
  };
  const PatchRecord::Ref b = out.setObject(PatchRecord::kRoot, "b");
  for (int i = 0; i <= 3; ++i)
    for (int j = 0; i + j <= 3; ++j) out.set(b, name('b', i, j, 3 - i - j), patch.b[i][j]);
  const PatchRecord::Ref n = out.setObject(PatchRecord::kRoot, "n");
  for (int i = 0; i <= 2; ++i)
    for (int j = 0; i + j <= 2; ++j) out.set(n, name('n', i, j, 2 - i - j), patch.n[i][j]);
}

}  // namespace quadtri
