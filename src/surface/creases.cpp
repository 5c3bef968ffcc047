#include "quadtri/surface/creases.h"

#include <atomic>
#include <cmath>

#include "quadtri/math/least_squares.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/edge_curves.h"

namespace quadtri {
namespace {

// As edgeControlPoint: negligible where the constraints meet at a real angle, decisive where a
// direction is left free (a straight crease leaves the one along the edge free).
constexpr double kCreaseDamping = 1e-7;

// The end of an edge at position index v from its sides' unit corner normals there.
EdgeEnd classifyEnd(const std::vector<Vec3>& normals, const Vec3& chord) {
  EdgeEnd end;
  bool allEqual = true;
  for (const Vec3& n : normals) allEqual &= n == normals.front();
  if (allEqual) return end;  // Shared
  const double minCos = std::cos(kCreaseMinDegrees * kPi / 180.0);
  bool close = true;
  Vec3 sum = Vec3::Zero();
  for (const Vec3& a : normals) {
    sum += a;
    for (const Vec3& b : normals) close &= a.dot(b) >= minCos;
  }
  if (close) {
    end.kind = EdgeEnd::Kind::Merged;
    end.normal = safeNormalized(sum, normals.front());
    return end;
  }
  end.kind = EdgeEnd::Kind::Crease;
  const Vec3 straight = safeNormalized(chord, Vec3(1, 0, 0));
  if (normals.size() != 2) {
    end.direction = straight;
    return end;
  }
  const Vec3 cross = normals[0].cross(normals[1]);
  // |n₁ × n₂| below sin 1°: the normals are nearly opposite (nearly equal ones merged above).
  end.direction = cross.norm() > std::sin(kCreaseMinDegrees * kPi / 180.0)
                      ? Vec3(cross.normalized())
                      : straight;
  return end;
}

// True when every corner at a position takes one normal index there, and every normal that
// index names has a direction: then each side of every edge end carries the same unit normal,
// and every end is Shared. One pass over the corners, where classifying the ends normalises two
// normals per side of every edge (an eighth of a `pn` conversion on a smooth million-triangle
// mesh).
bool everyEndShared(const TriangleMesh& mesh) {
  std::vector<uint32_t> normalAt(mesh.positions.size(), UINT32_MAX);
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t& at = normalAt[mesh.triangles[t][k]];
      const uint32_t n = mesh.normalIndices[t][k];
      if (at == UINT32_MAX)
        at = n;
      else if (at != n)
        return false;
    }
  for (const uint32_t n : normalAt)
    if (n != UINT32_MAX && safeNormalized(mesh.normals[n], Vec3::Zero()) == Vec3::Zero())
      return false;  // unitCornerNormal falls back to each side's own face normal there
  return true;
}

}  // namespace

Vec3 EdgeEnd::tangentPart(const Vec3& e, const Vec3& own) const {
  if (kind == Kind::Crease) return e.dot(direction) * direction;
  const Vec3& n = normalFor(own);
  return e - e.dot(n) * n;
}

EdgeEnds edgeEnds(const TriangleMesh& mesh) {
  if (!edgeEndsNeedTopology(mesh)) return EdgeEnds(mesh.triangleCount());
  return EdgeEnds::classify(mesh, mesh.topology());
}

bool edgeEndsNeedTopology(const TriangleMesh& mesh) {
  return mesh.hasNormals() && !everyEndShared(mesh);
}

EdgeEnds edgeEnds(const TriangleMesh& mesh, const MeshTopology& topo) {
  if (!mesh.hasNormals() || everyEndShared(mesh)) return EdgeEnds(mesh.triangleCount());
  return EdgeEnds::classify(mesh, topo);
}

EdgeEnds EdgeEnds::classify(const TriangleMesh& mesh, const MeshTopology& topo) {
  EdgeEnds out(mesh.triangleCount());
  // The ends of edge e from the corner normals of its sides (na, nb: reused buffers for them).
  const auto classify = [&](size_t e, std::vector<Vec3>& na, std::vector<Vec3>& nb) {
    const Edge& edge = topo.edges[e];
    na.clear();
    nb.clear();
    for (auto [t, k] : edge.sides) {
      const bool forward = mesh.triangles[t][k] == edge.a;
      const int ka = forward ? k : (k + 1) % 3, kb = forward ? (k + 1) % 3 : k;
      na.push_back(mesh.unitCornerNormal(t, ka));
      nb.push_back(mesh.unitCornerNormal(t, kb));
    }
    const Vec3 chord = mesh.positions[edge.b] - mesh.positions[edge.a];
    return std::array<EdgeEnd, 2>{classifyEnd(na, chord), classifyEnd(nb, chord)};
  };
  // Pass 1 marks the edges with an end that is not Shared and their triangles; pass 2 stores
  // those triangles' ends. Each edge writes only its own slots, so neither pass depends on the
  // thread count. The normals' buffers are reused within a block of edges.
  std::vector<uint8_t> splitEdge(topo.edges.size(), 0);
  std::vector<std::atomic<uint8_t>> splitTriangle(mesh.triangleCount());
  parallelForRange(
      tbb::blocked_range<size_t>(0, topo.edges.size(), 4096),
      [&](const tbb::blocked_range<size_t>& range) {
        std::vector<Vec3> na, nb;
        for (size_t e = range.begin(); e != range.end(); ++e) {
          const auto ends = classify(e, na, nb);
          if (ends[0].kind == EdgeEnd::Kind::Shared && ends[1].kind == EdgeEnd::Kind::Shared)
            continue;
          splitEdge[e] = 1;
          for (auto [t, k] : topo.edges[e].sides)
            splitTriangle[t].store(1, std::memory_order_relaxed);
        }
      });
  size_t stored = 0;
  for (const auto& flag : splitTriangle) stored += flag.load(std::memory_order_relaxed);
  if (stored == 0) return out;
  out.slot_.assign(mesh.triangleCount(), EdgeEnds::kShared);
  out.stored_.resize(stored);
  uint32_t next = 0;
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    if (splitTriangle[t].load(std::memory_order_relaxed)) out.slot_[t] = next++;
  parallelForRange(tbb::blocked_range<size_t>(0, topo.edges.size(), 4096),
                   [&](const tbb::blocked_range<size_t>& range) {
                     std::vector<Vec3> na, nb;
                     for (size_t e = range.begin(); e != range.end(); ++e) {
                       if (!splitEdge[e]) continue;
                       const auto [a, b] = classify(e, na, nb);
                       const Edge& edge = topo.edges[e];
                       for (auto [t, k] : edge.sides) {
                         const bool forward = mesh.triangles[t][k] == edge.a;
                         out.stored_[out.slot_[t]][k] =
                             forward ? std::array<EdgeEnd, 2>{a, b} : std::array<EdgeEnd, 2>{b, a};
                       }
                     }
                   });
  return out;
}

bool hasSplitEdges(const EdgeEnds& ends) {
  return ends.anySplit();
}

Vec3 creaseControlPoint(const Vec3& vaIn, const EdgeEnd& eaIn, const Vec3& naIn, const Vec3& vbIn,
                        const EdgeEnd& ebIn, const Vec3& nbIn) {
  // Canonical order (positions differ on a real edge) makes both sides compute the same bits.
  const bool swap = edgeEndsSwapped(vaIn, Vec3::Zero(), vbIn, Vec3::Zero());
  const Vec3& va = swap ? vbIn : vaIn;
  const Vec3& vb = swap ? vaIn : vbIn;
  const EdgeEnd& ea = swap ? ebIn : eaIn;
  const EdgeEnd& eb = swap ? eaIn : ebIn;
  const Vec3& na = swap ? nbIn : naIn;
  const Vec3& nb = swap ? naIn : nbIn;
  const Vec3 e = vb - va;
  const double len = e.norm();
  const Vec3 mid = 0.5 * (va + vb);
  if (!(len > 0.0)) return mid;
  // b = mid + δ. A smooth end v (unit normal n) asks n·(b − v) = 0; a crease end asks the same
  // of two unit vectors u₁, u₂ normal to its direction d, i.e. b − v ∥ d.
  Eigen::Matrix<double, 7, 3> A = Eigen::Matrix<double, 7, 3>::Zero();
  Eigen::Matrix<double, 7, 1> r = Eigen::Matrix<double, 7, 1>::Zero();
  int rows = 0;
  auto addEnd = [&](const EdgeEnd& end, const Vec3& own, const Vec3& v) {
    auto row = [&](const Vec3& n) {
      A.row(rows) = n.transpose();
      r[rows++] = n.dot(v - mid);
    };
    if (!end.crease()) {
      row(end.normalFor(own));
      return;
    }
    Vec3 u1, u2;
    orthonormalBasis(end.direction, u1, u2);
    row(u1);
    row(u2);
  };
  addEnd(ea, na, va);
  addEnd(eb, nb, vb);
  // The damping rows sit below the constraints; unused constraint rows stay zero.
  A.bottomRows<3>() = kCreaseDamping * Mat3::Identity();
  Vec3 delta;
  if (!householderLeastSquares(A, r, delta, 0.0)) delta.setConstant(std::nan(""));
  // Taken when b lies within half the chord of its midpoint and over its middle half, so that
  // neither end's tangent 2(b − v) has less than half the chord's length along the chord.
  if (allFinite(delta) && delta.norm() <= 0.5 * len && std::abs(delta.dot(e)) <= 0.25 * len * len)
    return mid + delta;
  // The quadratic nearest the cubic Hermite edge with end tangents T_a(e), T_b(e) (its control
  // points va + T_a(e)/3 and vb − T_b(e)/3, degree-reduced): always within len/2 of mid.
  return mid + 0.25 * (ea.tangentPart(e, na) - eb.tangentPart(e, nb));
}

}  // namespace quadtri
