#include "quadtri/analysis/crack_rate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <iterator>
#include <optional>
#include <vector>

#include "quadtri/geometry/rng.h"
#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"

namespace quadtri {
namespace {

// Exact crossing parity of a line with a triangle mesh, given Embree's hits as candidates.
class TriangleCrossings {
 public:
  explicit TriangleCrossings(const TriangleMesh& mesh) : mesh_(mesh) {
    // Vertex → triangles, compressed.
    ringStart_.assign(mesh.positions.size() + 1, 0);
    for (const Tri& tri : mesh.triangles)
      for (uint32_t v : tri) ++ringStart_[v + 1];
    for (size_t v = 0; v < mesh.positions.size(); ++v) ringStart_[v + 1] += ringStart_[v];
    ring_.resize(ringStart_.back());
    std::vector<uint32_t> fill(ringStart_.begin(), ringStart_.end() - 1);
    for (uint32_t t = 0; t < mesh.triangles.size(); ++t)
      for (uint32_t v : mesh.triangles[t]) ring_[fill[v]++] = t;
  }

  /// Buffers of count(), kept across lines.
  struct Scratch {
    std::vector<uint32_t> tested, known, pending, fresh, merged;
  };

  /// Triangles crossed by the line o + s·d among the vertex one-rings of the candidates and,
  /// in turn, of every crossed triangle's vertices: where the surface folds over itself within
  /// float precision (three sheets 1e-3 of an edge apart on `quadric-param`'s tessellation of
  /// `eight`), Embree may report one sheet of the fold and the line's crossings of the other
  /// two lie beyond its one-ring. Each round works on sorted sets, so a line with n hits costs
  /// O(n log n), not O(n²).
  size_t count(const Vec3& o, const Vec3& d, const std::vector<RayHit>& candidates,
               Scratch& scratch) const {
    std::vector<uint32_t>& tested = scratch.tested;    // triangles tested so far, sorted
    std::vector<uint32_t>& known = scratch.known;      // vertices whose rings are tested, sorted
    std::vector<uint32_t>& pending = scratch.pending;  // vertices whose rings are next, sorted
    std::vector<uint32_t>& fresh = scratch.fresh;
    std::vector<uint32_t>& merged = scratch.merged;
    const auto sortUnique = [](std::vector<uint32_t>& v) {
      std::sort(v.begin(), v.end());
      v.erase(std::unique(v.begin(), v.end()), v.end());
    };
    // a ← a ∪ b, both sorted.
    const auto unite = [&merged](std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
      merged.clear();
      std::set_union(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(merged));
      a.swap(merged);
    };
    tested.clear();
    known.clear();
    pending.clear();
    for (const RayHit& hit : candidates)
      for (uint32_t v : mesh_.triangles[hit.primitive]) pending.push_back(v);
    sortUnique(pending);
    size_t crossed = 0;
    while (!pending.empty()) {
      fresh.clear();
      for (uint32_t v : pending)
        fresh.insert(fresh.end(), ring_.begin() + ringStart_[v], ring_.begin() + ringStart_[v + 1]);
      sortUnique(fresh);
      unite(known, pending);
      // Only the triangles not tested in an earlier round.
      merged.clear();
      std::set_difference(fresh.begin(), fresh.end(), tested.begin(), tested.end(),
                          std::back_inserter(merged));
      fresh.swap(merged);
      pending.clear();
      for (uint32_t t : fresh)
        if (crosses(t, o, d)) {
          ++crossed;
          for (uint32_t v : mesh_.triangles[t]) pending.push_back(v);
        }
      unite(tested, fresh);
      // The crossed triangles' vertices whose rings are not tested yet.
      sortUnique(pending);
      merged.clear();
      std::set_difference(pending.begin(), pending.end(), known.begin(), known.end(),
                          std::back_inserter(merged));
      pending.swap(merged);
    }
    return crossed;
  }

 private:
  // Side of the line relative to the directed edge a→b, from the undirected edge's own sign
  // (lower index first; zero counts as positive), so both triangles of an edge agree exactly.
  bool edgeSide(uint32_t a, uint32_t b, const Vec3& o, const Vec3& d) const {
    const uint32_t lo = std::min(a, b), hi = std::max(a, b);
    const bool positive = d.dot((mesh_.positions[lo] - o).cross(mesh_.positions[hi] - o)) >= 0.0;
    return a == lo ? positive : !positive;
  }
  // The line passes through the triangle when it lies on the same side of all three edges.
  bool crosses(uint32_t t, const Vec3& o, const Vec3& d) const {
    const Tri& tri = mesh_.triangles[t];
    const bool s0 = edgeSide(tri[0], tri[1], o, d);
    return edgeSide(tri[1], tri[2], o, d) == s0 && edgeSide(tri[2], tri[0], o, d) == s0;
  }

  const TriangleMesh& mesh_;
  std::vector<uint32_t> ringStart_, ring_;
};

// Whether two hits may be one point of a boundary their primitives share (always true where a
// hit does not know its triangles): their triangles share an edge (or are one), or they share
// one vertex and both hits lie within `near` of it (the only point two such primitives have
// in common).
bool mayShareBoundary(const LineHit& a, const LineHit& b, const std::vector<Vec3>& positions,
                      double near) {
  if (a.vertices[0] == ~0u || b.vertices[0] == ~0u) return true;
  uint32_t first = ~0u;
  for (uint32_t va : a.vertices)
    for (uint32_t vb : b.vertices) {
      if (va == ~0u || va != vb || va == first) continue;
      if (first != ~0u) return true;  // a second shared vertex
      first = va;
    }
  if (first == ~0u) return false;
  return (a.point - positions[first]).norm() < near && (b.point - positions[first]).norm() < near;
}

// A Bézier hit within this of its piece's boundary (in the piece's barycentric coordinates) may
// be the same point as its neighbour's hit; one farther inside is a crossing of its own.
constexpr double kBoundaryBarycentric = 1e-6;

}  // namespace

size_t patchCrossings(std::vector<LineHit>& line, double mergeDistance,
                      const std::vector<Vec3>& positions) {
  std::sort(line.begin(), line.end(), [](const LineHit& a, const LineHit& b) { return a.s < b.s; });
  size_t crossings = 0;
  std::vector<size_t> group;
  const double near = 10.0 * mergeDistance;
  for (size_t i = 0; i < line.size();) {
    size_t j = i;
    while (j < line.size() && (j == i || line[j].s - line[j - 1].s < mergeDistance)) ++j;
    // Groups: each hit joins the first group all of whose hits it may share a boundary with.
    group.assign(j - i, ~size_t(0));
    size_t groups = 0;
    for (size_t a = i; a < j; ++a) {
      if (!line[a].shared) {
        ++crossings;
        continue;
      }
      for (size_t g = 0; g < groups && group[a - i] == ~size_t(0); ++g) {
        bool all = true;
        for (size_t b = i; b < a && all; ++b)
          all = group[b - i] != g || mayShareBoundary(line[a], line[b], positions, near);
        if (all) group[a - i] = g;
      }
      if (group[a - i] == ~size_t(0)) group[a - i] = groups++;
    }
    for (size_t g = 0; g < groups; ++g) {
      long balance = 0;
      for (size_t b = i; b < j; ++b)
        if (group[b - i] == g) balance += line[b].entering ? 1 : -1;
      crossings += balance != 0 ? 1 : 2;
    }
    i = j;
  }
  return crossings;
}

size_t triangleCrossings(const TriangleMesh& mesh, const Vec3& o, const Vec3& d,
                         const std::vector<uint32_t>& candidates) {
  std::vector<RayHit> hits(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) {
    if (candidates[i] >= mesh.triangleCount())
      fail("triangle crossings: candidate {} is not a triangle of the mesh ({} triangles)",
           candidates[i], mesh.triangleCount());
    hits[i].primitive = candidates[i];
  }
  TriangleCrossings::Scratch scratch;
  return TriangleCrossings(mesh).count(o, d, hits, scratch);
}

double crackRate(const ModelGeometry& geometry, const CrackRateOptions& options) {
  if (options.lines == 0) fail("crack rate: the number of lines must be positive");
  Accel accel(Accel::Options{true, true});  // robust, reporting every hit
  addModelGeometry(accel, geometry);
  accel.commit();
  const Bounds3 geometryBox = accel.bounds();
  if (geometryBox.empty()) fail("crack rate: the geometry is empty");
  if (const std::optional<Bounds3>& given = options.lineBox) {
    for (int a = 0; a < 3; ++a)
      if (!std::isfinite(given->lo[a]) || !std::isfinite(given->hi[a]) ||
          !(given->lo[a] <= given->hi[a]) ||
          !(std::max(std::abs(given->lo[a]), std::abs(given->hi[a])) <= Accel::kLargestCoordinate))
        fail(
            "crack rate: the line box [{}, {}] × [{}, {}] × [{}, {}] is not a box of finite "
            "coordinates within ±{:g} (the largest Embree traces)",
            given->lo.x(), given->hi.x(), given->lo.y(), given->hi.y(), given->lo.z(),
            given->hi.z(), Accel::kLargestCoordinate);
    if (!(given->diagonal().norm() > 0.0))
      fail("crack rate: the line box is a single point ({}, {}, {}); it needs an extent",
           given->lo.x(), given->lo.y(), given->lo.z());
  }
  Bounds3 box = options.lineBox.value_or(geometryBox);
  const double diagonal = box.diagonal().norm();
  box.inflate(options.boxMargin * diagonal);
  // The lines start inside the grown box and run both ways through it and through the
  // geometry's box, so where the margin would take their origins past what Embree traces
  // (geometry near its limit), the box is kept within that limit: any point of the line
  // serves as its origin.
  for (int a = 0; a < 3; ++a) {
    box.lo[a] = std::max(box.lo[a], -Accel::kLargestCoordinate);
    box.hi[a] = std::min(box.hi[a], Accel::kLargestCoordinate);
  }
  // Hits merge within the geometry's rounding, whatever box the lines come through.
  const double mergeDistance = 1e-7 * geometryBox.diagonal().norm();
  // From a point of the grown box, the grown box and the geometry's box lie within the
  // diagonal of their union.
  Bounds3 traced = box;
  traced.extend(geometryBox);
  const double reach = traced.diagonal().norm();
  const std::optional<TriangleCrossings> triangles =
      geometry.patches || geometry.bezier ? std::nullopt
                                          : std::optional<TriangleCrossings>(geometry.triangles);

  // The vertices of the triangles a primitive stands for (ModelGeometry::mesh).
  const TriangleMesh* mesh = geometry.mesh;
  const std::vector<Vec3> noPositions;
  const std::vector<Vec3>& positions = mesh ? mesh->positions : noPositions;
  const auto vertices = [&](const RayHit& h) {
    std::array<uint32_t, 6> out{~0u, ~0u, ~0u, ~0u, ~0u, ~0u};
    if (!mesh) return out;
    std::array<int64_t, 2> tris{-1, -1};
    if (geometry.bezier) {
      if (h.primitive < geometry.bezier->size()) tris[0] = (*geometry.bezier)[h.primitive].triangle;
    } else if (geometry.patches && h.primitive < geometry.patches->size()) {
      const QuadricPatch& p = (*geometry.patches)[h.primitive];
      if (p.isBridge())
        tris = {p.joins[0], p.joins[1]};
      else
        tris[0] = int64_t(h.primitive);
    }
    for (int k = 0; k < 2; ++k)
      if (tris[k] >= 0 && size_t(tris[k]) < mesh->triangleCount())
        for (int c = 0; c < 3; ++c) out[3 * k + c] = mesh->triangles[size_t(tris[k])][c];
    return out;
  };
  auto cracked = [&](const Vec3& p, const Vec3& d, std::vector<RayHit>& hits,
                     std::vector<LineHit>& line, TriangleCrossings::Scratch& scratch) {
    hits.clear();
    line.clear();
    for (const double sign : {1.0, -1.0}) {
      const size_t before = hits.size();
      accel.allHits(Ray{p, sign * d, 0.0, reach}, hits);
      for (size_t i = before; i < hits.size(); ++i) {
        const RayHit& h = hits[i];
        const bool shared =
            !geometry.bezier || std::min({h.u, h.v, 1.0 - h.u - h.v}) < kBoundaryBarycentric;
        line.push_back(
            {sign * h.t, h.geometricNormal.dot(d) < 0.0, shared, vertices(h), p + sign * h.t * d});
      }
    }
    const size_t crossings = triangles ? triangles->count(p, d, hits, scratch)
                                       : patchCrossings(line, mergeDistance, positions);
    return crossings % 2 == 1;
  };
  const size_t count = parallelReduce(
      tbb::blocked_range<size_t>(0, options.lines), size_t(0),
      [&](const tbb::blocked_range<size_t>& range, size_t sum) {
        const FlushToZeroScope flushToZero;
        std::vector<RayHit> hits;
        std::vector<LineHit> line;
        TriangleCrossings::Scratch scratch;
        for (size_t i = range.begin(); i != range.end(); ++i) {
          Pcg32 rng(options.seed, i);
          const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
          const Vec3 p = box.lo + box.diagonal().cwiseProduct(u);
          sum += cracked(p, uniformDirection(rng), hits, line, scratch);
        }
        return sum;
      },
      std::plus<size_t>());
  return double(count) / double(options.lines);
}

}  // namespace quadtri
