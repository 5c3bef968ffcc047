#include "quadtri/surface/tessellate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <unordered_map>

#include "quadtri/math/error.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/topology.h"

namespace quadtri {
namespace {

// Where a sample point of a patch lies: at a mesh corner, on a mesh edge at step `step` of
// `steps` from corner `from` to corner `to`, or inside the patch.
struct PointSite {
  enum class Kind { Corner, Edge, Interior } kind = Kind::Interior;
  int corner = 0;  // Corner
  int edge = 0;    // Edge: local edge k joins corners k and k+1
  int step = 0;    // Edge: steps from corner k towards corner k+1
};

// The parameter points of one patch and the local triangles over them.
struct PatchPattern {
  std::vector<Vec2> uv;
  std::vector<PointSite> sites;
  std::vector<Tri> triangles;
  int edgeSteps = 0;  // points along each edge, minus one
};

PatchPattern latticePattern(int n) {
  PatchPattern p;
  p.edgeSteps = n;
  std::vector<std::vector<uint32_t>> id(n + 1, std::vector<uint32_t>(n + 1));
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i + j <= n; ++i) {
      PointSite s;
      if (i == 0 && j == 0)
        s = {PointSite::Kind::Corner, 0, 0, 0};
      else if (i == n)
        s = {PointSite::Kind::Corner, 1, 0, 0};
      else if (j == n)
        s = {PointSite::Kind::Corner, 2, 0, 0};
      else if (j == 0)
        s = {PointSite::Kind::Edge, 0, 0, i};
      else if (i + j == n)
        s = {PointSite::Kind::Edge, 0, 1, j};
      else if (i == 0)
        s = {PointSite::Kind::Edge, 0, 2, n - j};
      id[i][j] = uint32_t(p.uv.size());
      p.uv.emplace_back(double(i) / n, double(j) / n);
      p.sites.push_back(s);
    }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i + j < n; ++i) {
      p.triangles.push_back({id[i][j], id[i + 1][j], id[i][j + 1]});
      if (i + j + 1 < n) p.triangles.push_back({id[i + 1][j], id[i + 1][j + 1], id[i][j + 1]});
    }
  return p;
}

// The thesis' m×m uv grid (m = 50: 2500 points, 2(m-1)² = 4802 triangles), mapped onto the
// triangle by (u, v) = (s(1-t), t): the t = 1 row collapses onto corner 2, so the triangles of
// the last strip that have two corners there are degenerate (m-1 of them). They are kept so
// the primitive count is the thesis' own.
PatchPattern thesisGridPattern(int m) {
  PatchPattern p;
  const int n = m - 1;
  p.edgeSteps = n;
  for (int b = 0; b <= n; ++b)
    for (int a = 0; a <= n; ++a) {
      const double s = double(a) / n, t = double(b) / n;
      PointSite site;
      if (b == n)
        site = {PointSite::Kind::Corner, 2, 0, 0};
      else if (a == 0 && b == 0)
        site = {PointSite::Kind::Corner, 0, 0, 0};
      else if (a == n && b == 0)
        site = {PointSite::Kind::Corner, 1, 0, 0};
      else if (b == 0)
        site = {PointSite::Kind::Edge, 0, 0, a};
      else if (a == n)
        site = {PointSite::Kind::Edge, 0, 1, b};
      else if (a == 0)
        site = {PointSite::Kind::Edge, 0, 2, n - b};
      p.uv.emplace_back(s * (1.0 - t), t);
      p.sites.push_back(site);
    }
  auto id = [&](int a, int b) { return uint32_t(b * (n + 1) + a); };
  for (int b = 0; b < n; ++b)
    for (int a = 0; a < n; ++a) {
      p.triangles.push_back({id(a, b), id(a + 1, b), id(a + 1, b + 1)});
      p.triangles.push_back({id(a, b), id(a + 1, b + 1), id(a, b + 1)});
    }
  return p;
}

}  // namespace

// The most points or normals a lattice can number: a 32-bit index, below the empty slot's ~0u.
constexpr uint64_t kMaxLatticeIndex = std::numeric_limits<uint32_t>::max() - 1;

namespace {

// Where the mesh splits normals (a crease), the welded points there keep each side's own
// surface normal: positions are shared, normals are per corner. Empty when the model welds
// nothing.
struct Splits {
  std::vector<bool> vertex, edge;
  bool any() const {
    return std::find(vertex.begin(), vertex.end(), true) != vertex.end() ||
           std::find(edge.begin(), edge.end(), true) != edge.end();
  }
};

Splits findSplits(const SurfaceModel& model) {
  Splits splits;
  const TriangleMesh& mesh = model.mesh();
  if (!model.sharesEdges() || model.representation() == Representation::InputTriangles)
    return splits;
  const MeshTopology& topo = mesh.topology();
  splits.vertex.assign(mesh.positions.size(), false);
  splits.edge.assign(topo.edges.size(), false);
  if (!mesh.hasNormals()) return splits;
  std::vector<Vec3> first(mesh.positions.size());
  std::vector<bool> seen(mesh.positions.size(), false);
  for (size_t t = 0; t < mesh.triangleCount(); ++t)
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = mesh.triangles[t][k];
      const Vec3 n = mesh.cornerNormal(t, k);
      if (!seen[v]) {
        seen[v] = true;
        first[v] = n;
      } else if (n != first[v]) {
        splits.vertex[v] = true;
      }
    }
  for (size_t e = 0; e < topo.edges.size(); ++e) {
    const Edge& edge = topo.edges[e];
    const auto [t0, k0] = edge.sides.front();
    const bool f0 = mesh.triangles[t0][k0] == edge.a;
    const Vec3 na = mesh.cornerNormal(t0, f0 ? k0 : (k0 + 1) % 3);
    const Vec3 nb = mesh.cornerNormal(t0, f0 ? (k0 + 1) % 3 : k0);
    for (auto [t, k] : edge.sides) {
      const bool forward = mesh.triangles[t][k] == edge.a;
      splits.edge[e] = splits.edge[e] || mesh.cornerNormal(t, forward ? k : (k + 1) % 3) != na ||
                       mesh.cornerNormal(t, forward ? (k + 1) % 3 : k) != nb;
    }
  }
  return splits;
}

// The walk that numbers a tessellation's points: each triangle, point by point, numbers the
// ones no triangle before it numbered (welded, a mesh vertex or edge point is numbered once).
// Only that numbering is sequential, and it evaluates nothing; firstPoint[t] is the first number
// triangle t gives, so triangle t's new points are the numbers firstPoint[t] to
// firstPoint[t + 1] - 1, and they can be evaluated, and the triangles indexed, in any order and
// in parallel, block by block too: the result does not depend on the threads.
class LatticeWalk {
 public:
  LatticeWalk(const SurfaceModel& model, const Tessellation& tessellation)
      : model_(model),
        mesh_(model.mesh()),
        pattern_(tessellation.kind == Tessellation::Kind::ThesisGrid
                     ? thesisGridPattern(tessellation.level)
                     : latticePattern(tessellation.level)),
        weld_(model.sharesEdges()),
        topo_(mesh_.topology()),
        steps_(pattern_.edgeSteps),
        splits_(findSplits(model)) {
    const size_t n = mesh_.triangleCount();
    cornerVertex_ = largeVector(weld_ ? mesh_.positions.size() : 0, ~0u);
    // Welded edge points: per mesh edge, `steps - 1` interior points from endpoint a to b.
    edgeVertex_ = largeVector(weld_ ? topo_.edges.size() * size_t(steps_ - 1) : 0, ~0u);
    firstPoint_ = largeVector<uint32_t>(n + 1);
    uint64_t next = 0;
    for (size_t t = 0; t < n; ++t) {
      firstPoint_[t] = uint32_t(next);
      for (size_t i = 0; i < points(); ++i) {
        bool split;
        uint32_t* slot = slotOf(t, i, split);
        if (slot && *slot != ~0u) continue;
        if (slot) *slot = uint32_t(next);
        if (++next > kMaxLatticeIndex)
          fail("tessellating {} patches at {} points each: more than {} points", n, points(),
               kMaxLatticeIndex);
      }
    }
    firstPoint_[n] = uint32_t(next);
    // Each corner's and edge point's index in the pattern (a corner's first: the thesis grid's
    // last row is all corner 2).
    cornerIndex_.fill(~size_t(0));
    for (std::vector<size_t>& e : edgeIndex_) e.assign(size_t(steps_) + 1, ~size_t(0));
    for (size_t i = points(); i-- > 0;) {
      const PointSite& s = pattern_.sites[i];
      if (s.kind == PointSite::Kind::Corner) cornerIndex_[size_t(s.corner)] = i;
      if (s.kind == PointSite::Kind::Edge) edgeIndex_[size_t(s.edge)][size_t(s.step)] = i;
    }
  }

  size_t patches() const { return mesh_.triangleCount(); }
  size_t points() const { return pattern_.uv.size(); }  // per patch
  size_t trianglesPerPatch() const { return pattern_.triangles.size(); }
  size_t pointCount() const { return firstPoint_.back(); }
  uint32_t firstPoint(size_t t) const { return firstPoint_[t]; }
  const PatchPattern& pattern() const { return pattern_; }
  /// Whether some welded point has another normal on each side (a crease): then the
  /// tessellation has more normals than points.
  bool creased() const { return splits_.any(); }

  /// Triangle t's point numbers, point by point (its own ones in the order it numbered them),
  /// whether it numbered each and whether the mesh splits normals there.
  void localPoints(size_t t, uint32_t* local, uint8_t* isNew, uint8_t* split) const {
    uint32_t own = firstPoint_[t];
    for (size_t i = 0; i < points(); ++i) {
      bool splitHere;
      const uint32_t* slot = slotOf(t, i, splitHere);
      split[i] = splitHere;
      isNew[i] = !slot || *slot == own;
      local[i] = isNew[i] ? own++ : *slot;
    }
  }

  /// The surface point and normal of point i of triangle t; corners are the mesh's own
  /// vertices, bit for bit.
  std::pair<Vec3, Vec3> evaluate(size_t t, size_t i) const {
    return finish(t, i, model_.evaluate(t, pattern_.uv[i].x(), pattern_.uv[i].y()));
  }
  /// evaluate(t, i) from the model's point sp at point i's (u, v).
  std::pair<Vec3, Vec3> finish(size_t t, size_t i, SurfacePoint sp) const {
    const PointSite& s = pattern_.sites[i];
    if (s.kind == PointSite::Kind::Corner) sp.position = mesh_.corner(t, s.corner);
    return {sp.position, safeNormalized(sp.normal, mesh_.faceNormal(t))};
  }

  /// Evaluates the points triangles [begin, end) number into positions and normals, point
  /// p at p - firstPoint(begin), and writes their triangles to triangles[(t - begin) * per
  /// patch + j] when it is not null.
  void evaluateBlock(size_t begin, size_t end, Vec3* positions, Vec3* normals,
                     Tri* triangles) const {
    const uint32_t base = firstPoint_[begin];
    parallelForRange(tbb::blocked_range<size_t>(begin, end, 256),
                     [&](const tbb::blocked_range<size_t>& range) {
                       std::vector<uint32_t> local(points());
                       std::vector<uint8_t> isNew(points()), split(points());
                       // The points a triangle numbers, evaluated together (evaluateMany).
                       std::vector<size_t> own;
                       std::vector<Vec2> ownUv;
                       std::vector<SurfacePoint> evaluated;
                       for (size_t t = range.begin(); t != range.end(); ++t) {
                         localPoints(t, local.data(), isNew.data(), split.data());
                         if (positions) {
                           own.clear();
                           ownUv.clear();
                           for (size_t i = 0; i < points(); ++i)
                             if (isNew[i]) own.push_back(i), ownUv.push_back(pattern_.uv[i]);
                           evaluated.resize(own.size());
                           model_.evaluateMany(t, ownUv.data(), own.size(), evaluated.data());
                           for (size_t j = 0; j < own.size(); ++j) {
                             const size_t i = own[j];
                             const auto [p, nrm] = finish(t, i, evaluated[j]);
                             positions[local[i] - base] = p;
                             normals[local[i] - base] = nrm;
                           }
                         }
                         if (triangles)
                           for (size_t j = 0; j < trianglesPerPatch(); ++j) {
                             const Tri& tri = pattern_.triangles[j];
                             triangles[(t - begin) * trianglesPerPatch() + j] = {
                                 local[tri[0]], local[tri[1]], local[tri[2]]};
                           }
                       }
                     });
  }

  /// Triangle t's crease normals: where it reuses a point at a split vertex or edge, its own
  /// surface normal there, when it differs from the one the point was numbered with
  /// (numbered(t, i, point)), in the order of its points.
  struct CreaseNormal {
    size_t i;        // the point's index in the pattern
    uint32_t point;  // its number
    Vec3 normal;
  };
  template <typename Numbered>
  void creaseNormals(size_t t, const Numbered& numbered, std::vector<CreaseNormal>& found) const {
    found.clear();
    std::vector<uint32_t> local(points());
    std::vector<uint8_t> isNew(points()), split(points());
    localPoints(t, local.data(), isNew.data(), split.data());
    for (size_t i = 0; i < points(); ++i) {
      if (isNew[i] || !split[i]) continue;
      const Vec3 normal = evaluate(t, i).second;
      if (normal != numbered(t, i, local[i])) found.push_back({i, local[i], normal});
    }
  }

  /// The position and normal that point i of triangle t (a welded point: a mesh vertex or an
  /// edge point) was numbered with, by the patch that numbered it: the last patch whose first
  /// number is at most the point's, at its own index of that vertex or edge point.
  std::pair<Vec3, Vec3> numberedPoint(size_t t, size_t i) const {
    bool split;
    const uint32_t* slot = slotOf(t, i, split);
    if (!slot) return evaluate(t, i);
    const size_t owner = size_t(std::upper_bound(firstPoint_.begin(), firstPoint_.end(), *slot) -
                                firstPoint_.begin()) -
                         1;
    const PointSite& s = pattern_.sites[i];
    if (s.kind == PointSite::Kind::Corner) {
      const uint32_t v = mesh_.triangles[t][s.corner];
      for (int k = 0; k < 3; ++k)
        if (mesh_.triangles[owner][k] == v) return evaluate(owner, cornerIndex_[k]);
    } else {
      const uint32_t e = topo_.edgeOf[t][s.edge];
      const int fromA = mesh_.triangles[t][s.edge] == topo_.edges[e].a ? s.step : steps_ - s.step;
      for (int k = 0; k < 3; ++k)
        if (topo_.edgeOf[owner][k] == e) {
          const bool ownerFromA = mesh_.triangles[owner][k] == topo_.edges[e].a;
          return evaluate(owner, edgeIndex_[k][size_t(ownerFromA ? fromA : steps_ - fromA)]);
        }
    }
    fail("tessellation: point {} of patch {} is not on patch {}, which numbered it", i, t, owner);
  }

 private:
  // The welded slot of point i of triangle t (its mesh vertex's or its edge point's), or null
  // for a point of its own; `split` where the mesh splits normals there.
  uint32_t* slotOf(size_t t, size_t i, bool& split) const {
    const PointSite& s = pattern_.sites[i];
    split = false;
    if (weld_ && s.kind == PointSite::Kind::Corner) {
      const uint32_t v = mesh_.triangles[t][s.corner];
      split = splits_.vertex[v];
      return &cornerVertex_[v];
    }
    if (weld_ && s.kind == PointSite::Kind::Edge) {
      const uint32_t e = topo_.edgeOf[t][s.edge];
      const bool fromA = mesh_.triangles[t][s.edge] == topo_.edges[e].a;
      const int step = fromA ? s.step : steps_ - s.step;
      split = splits_.edge[e];
      return &edgeVertex_[size_t(e) * size_t(steps_ - 1) + size_t(step - 1)];
    }
    return nullptr;
  }

  const SurfaceModel& model_;
  const TriangleMesh& mesh_;
  const PatchPattern pattern_;
  const bool weld_;
  const MeshTopology& topo_;
  const int steps_;
  const Splits splits_;
  mutable std::vector<uint32_t> cornerVertex_, edgeVertex_;  // filled by the numbering only
  std::vector<uint32_t> firstPoint_;
  std::array<size_t, 3> cornerIndex_{};
  std::array<std::vector<size_t>, 3> edgeIndex_;
};

}  // namespace

namespace {

// Crease normals: where a triangle reuses a point at a split vertex or edge, its own surface
// normal there, when it differs from the one the point was numbered with (numbered(t, i, point)),
// becomes an extra normal after the points' ones, numbered in the order of the walk. They are
// counted per patch (extraBefore[t]: how many the patches before t have), then written at those
// counts; the few points they sit on are evaluated again each time.
template <typename Numbered>
std::vector<size_t> countCreaseNormals(const LatticeWalk& walk, const Numbered& numbered) {
  const size_t n = walk.patches();
  std::vector<size_t> extraBefore = largeVector<size_t>(n + 1);
  parallelForRange(tbb::blocked_range<size_t>(0, n, 256),
                   [&](const tbb::blocked_range<size_t>& range) {
                     std::vector<LatticeWalk::CreaseNormal> found;
                     for (size_t t = range.begin(); t != range.end(); ++t) {
                       walk.creaseNormals(t, numbered, found);
                       extraBefore[t + 1] = found.size();
                     }
                   });
  for (size_t t = 0; t < n; ++t) extraBefore[t + 1] += extraBefore[t];
  if (walk.pointCount() + extraBefore[n] > kMaxLatticeIndex)
    fail("tessellating {} patches: more than {} normals", n, kMaxLatticeIndex);
  return extraBefore;
}

// For patches [begin, end): each extra normal f of patch t goes to extra(k, crease) with k =
// extraBefore[t] - extraBefore[begin] + f, and the corners of its triangles at that point
// (normalIndices[(t - begin) * per patch + j]) take its number, the points' count plus
// extraBefore[t] + f.
template <typename Numbered, typename Extra>
void writeCreaseNormals(const LatticeWalk& walk, const std::vector<size_t>& extraBefore,
                        const Numbered& numbered, size_t begin, size_t end, Tri* normalIndices,
                        const Extra& extra) {
  const size_t perPatch = walk.trianglesPerPatch();
  const PatchPattern& pattern = walk.pattern();
  parallelForRange(tbb::blocked_range<size_t>(begin, end, 256),
                   [&](const tbb::blocked_range<size_t>& range) {
                     std::vector<LatticeWalk::CreaseNormal> found;
                     for (size_t t = range.begin(); t != range.end(); ++t) {
                       if (extraBefore[t] == extraBefore[t + 1]) continue;
                       walk.creaseNormals(t, numbered, found);
                       for (size_t f = 0; f < found.size(); ++f) {
                         extra(extraBefore[t] - extraBefore[begin] + f, t, found[f]);
                         const auto index = uint32_t(walk.pointCount() + extraBefore[t] + f);
                         if (!normalIndices) continue;
                         for (size_t j = 0; j < perPatch; ++j)
                           for (int c = 0; c < 3; ++c)
                             if (size_t(pattern.triangles[j][c]) == found[f].i)
                               normalIndices[(t - begin) * perPatch + j][c] = index;
                       }
                     }
                   });
}

// The tessellation that walk numbers, whole.
TriangleMesh tessellateWalk(const LatticeWalk& walk) {
  const size_t n = walk.patches(), perPatch = walk.trianglesPerPatch();
  TriangleMesh out;
  resizeLarge(out.positions, walk.pointCount());
  resizeLarge(out.normals, walk.pointCount());
  resizeLarge(out.triangles, n * perPatch);
  walk.evaluateBlock(0, n, out.positions.data(), out.normals.data(), out.triangles.data());
  resizeLarge(out.normalIndices, out.triangles.size());
  out.normalIndices = out.triangles;
  if (!walk.creased()) return out;
  const auto numbered = [&](size_t, size_t, uint32_t p) { return out.normals[p]; };
  const std::vector<size_t> extraBefore = countCreaseNormals(walk, numbered);
  if (extraBefore[n] == 0) return out;
  const size_t base = out.normals.size();
  out.normals.resize(base + extraBefore[n]);
  writeCreaseNormals(walk, extraBefore, numbered, 0, n, out.normalIndices.data(),
                     [&](size_t k, size_t, const LatticeWalk::CreaseNormal& c) {
                       out.normals[base + k] = c.normal;
                     });
  return out;
}

}  // namespace

TriangleMesh tessellate(const SurfaceModel& model, const Tessellation& requested) {
  if (model.representation() == Representation::InputTriangles) return model.mesh();
  return tessellateWalk(LatticeWalk(model, resolveTessellation(model, requested)));
}

size_t saveTessellation(const SurfaceModel& model, const Tessellation& requested,
                        const std::filesystem::path& path, size_t blockPoints) {
  // The input triangles are written as they are, not copied first.
  if (model.representation() == Representation::InputTriangles) {
    saveMesh(model.mesh(), path);
    return model.mesh().triangleCount();
  }
  const LatticeWalk walk(model, resolveTessellation(model, requested));
  // A block's points are the numbers its patches give, its extra normals (creases) the ones
  // extraBefore gives them.
  const size_t n = walk.patches(), perPatch = walk.trianglesPerPatch();
  const size_t blockPatches = std::max<size_t>(1, blockPoints / walk.points());
  const auto range = [&](size_t b) {
    return std::pair(b * blockPatches, std::min(n, (b + 1) * blockPatches));
  };
  // The normal (and position) a point was numbered with, evaluated again by its patch.
  const auto numbered = [&](size_t t, size_t i, uint32_t) {
    return walk.numberedPoint(t, i).second;
  };
  const std::vector<size_t> extraBefore =
      walk.creased() ? countCreaseNormals(walk, numbered) : std::vector<size_t>();
  MeshStream stream;
  stream.points = walk.pointCount();
  stream.extraNormals = extraBefore.empty() ? 0 : extraBefore.back();
  stream.triangles = n * perPatch;
  stream.blocks = (n + blockPatches - 1) / blockPatches;
  stream.blockPoints = [&](size_t b, std::vector<Vec3>& positions, std::vector<Vec3>& normals) {
    const auto [begin, end] = range(b);
    const size_t count = walk.firstPoint(end) - walk.firstPoint(begin);
    positions.resize(count);
    normals.resize(count);
    walk.evaluateBlock(begin, end, positions.data(), normals.data(), nullptr);
  };
  stream.blockExtraNormals = [&](size_t b, std::vector<Vec3>& positions,
                                 std::vector<Vec3>& normals) {
    if (stream.extraNormals == 0) return;
    const auto [begin, end] = range(b);
    positions.resize(extraBefore[end] - extraBefore[begin]);
    normals.resize(positions.size());
    writeCreaseNormals(walk, extraBefore, numbered, begin, end, nullptr,
                       [&](size_t k, size_t t, const LatticeWalk::CreaseNormal& c) {
                         positions[k] = walk.numberedPoint(t, c.i).first;
                         normals[k] = c.normal;
                       });
  };
  stream.blockTriangles = [&](size_t b, std::vector<Tri>& triangles,
                              std::vector<Tri>& normalIndices) {
    const auto [begin, end] = range(b);
    triangles.resize((end - begin) * perPatch);
    walk.evaluateBlock(begin, end, nullptr, nullptr, triangles.data());
    if (stream.extraNormals == 0) return;  // every corner's normal is its point's
    normalIndices = triangles;
    writeCreaseNormals(walk, extraBefore, numbered, begin, end, normalIndices.data(),
                       [](size_t, size_t, const LatticeWalk::CreaseNormal&) {});
  };
  saveMeshStream(stream, path);
  return stream.triangles;
}

}  // namespace quadtri
