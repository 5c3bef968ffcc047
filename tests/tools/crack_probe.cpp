// crack_probe MESH [--lines N] [--seed S] [--normals average] [--show K] [--stray F]
//
// A diagnostic of `quadric-implicit-robust` on a closed mesh: draws the crack-rate lines of
// analysis/crack_rate.cpp (same seed, same streams, same box), counts their crossings as
// crackRate does, and for each cracked line prints its model crossings (patch or bridge, t,
// entering) beside its exact crossings of the flat triangles, and the mesh feature (vertex,
// edge, face) nearest to the first crossing the two disagree on. For every quadric root near
// that point it says which test kept or dropped it (edge plane, slab, bounds, bridge
// classification). It also reports hits farther than F mean edge lengths from their triangles
// (stray sheets), the widest gaps between neighbours' boundaries along each edge (in units of
// crackRate's merge distance), the lines whose crossings do not alternate between entering and
// leaving, and how many cracked lines are even when each cluster of hits within the merge
// distance counts its changes of direction (crackRate counts a cluster by its balance of
// entering and leaving hits: one crossing unless it enters as often as it leaves). Not a
// test: a tool for finding causes.
#include <fmt/core.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <optional>
#include <string>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/math/parallel.h"
#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_implicit_model.h"

using namespace quadtri;

namespace {

struct Hit {
  double s;
  bool entering;
  size_t primitive;
};

// Distance from p to triangle (a, b, c).
double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const Vec3 n = ab.cross(ac);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vec3 q = p - (n.dot(ap) / n2) * n;
    const double u = (q - a).cross(c - a).dot(n) / n2;  // weight of b
    const double v = (b - a).cross(q - a).dot(n) / n2;  // weight of c
    if (u >= 0 && v >= 0 && u + v <= 1) return (p - q).norm();
  }
  const auto seg = [&](const Vec3& x, const Vec3& y) {
    const Vec3 d = y - x;
    const double t =
        d.squaredNorm() > 0 ? std::clamp((p - x).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - (x + t * d)).norm();
  };
  return std::min({seg(a, b), seg(b, c), seg(c, a)});
}

// Exact-enough crossing of the line o + s d with triangle t: s, barycentrics, entering.
bool lineTriangle(const TriangleMesh& m, size_t t, const Vec3& o, const Vec3& d, double& s,
                  Vec3& bary, bool& entering) {
  const Vec3 a = m.corner(t, 0), b = m.corner(t, 1), c = m.corner(t, 2);
  const double w0 = d.dot((b - o).cross(c - o));
  const double w1 = d.dot((c - o).cross(a - o));
  const double w2 = d.dot((a - o).cross(b - o));
  if (!((w0 >= 0 && w1 >= 0 && w2 >= 0) || (w0 <= 0 && w1 <= 0 && w2 <= 0))) return false;
  const double sum = w0 + w1 + w2;
  if (sum == 0) return false;
  bary = Vec3(w0, w1, w2) / sum;
  const Vec3 p = bary[0] * a + bary[1] * b + bary[2] * c;
  s = (p - o).dot(d);
  entering = m.faceCross(t).dot(d) < 0;
  return true;
}

const char* planeName(const QuadricPatch& p, int i) {
  if (p.isBridge()) {
    static const char* names[] = {"slabA-lo", "slabA-hi", "slabB-lo", "slabB-hi", "end-a", "end-b"};
    return names[i];
  }
  static const char* names[] = {"edge0", "edge1", "edge2", "slab-lo", "slab-hi", "p5"};
  return names[i];
}

// Every root of primitive i's quadric on the line within [s0, s1], with the test that drops it.
struct RootNote {
  double s;
  std::string why;  // empty: kept
  bool bridge;
};

std::vector<RootNote> explainRoots(const RobustImplicitModel& model, size_t i, const Vec3& o,
                                   const Vec3& d, double s0, double s1, bool print) {
  std::vector<RootNote> notes;
  const auto& all = model.renderPatches();
  const QuadricPatch& patch = all[i];
  const QuadricCoeffs& q = patch.q;
  const double a = q[0] * d.x() * d.x() + q[1] * d.y() * d.y() + q[2] * d.z() * d.z() +
                   q[3] * d.x() * d.y() + q[4] * d.x() * d.z() + q[5] * d.y() * d.z();
  const double b = quadricGradient(q, o).dot(d);
  const double c = evalQuadric(q, o);
  std::vector<double> roots;
  if (std::abs(a) <= 1e-14 * (std::abs(b) + 1e-300)) {
    if (b != 0) roots.push_back(-c / b);
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
      roots.push_back(h / a);
      if (h != 0) roots.push_back(c / h);
    }
  }
  for (double s : roots) {
    if (s < s0 || s > s1) continue;
    const Vec3 p = o + s * d;
    std::string why, reasons;
    for (int k = 0; k < patch.planeCount; ++k) {
      const double v = patch.planes[k].head<3>().dot(p) + patch.planes[k][3];
      if (v < 0) {
        why += fmt::format(" out:{}({:.2e})", planeName(patch, k), v);
        std::string name = planeName(patch, k);
        name = name.substr(0, name.find_first_of("0123456789-AB"));
        if (reasons.find(name) == std::string::npos) reasons += " " + name;
      }
    }
    if ((p.array() < patch.bounds.lo.array()).any() || (p.array() > patch.bounds.hi.array()).any())
      why += " out:bounds", reasons += " bounds";
    if (patch.isBridge() && !bridgeCovers(all, patch, p))
      why += " out:same-side", reasons += " same-side";
    notes.push_back({s, reasons, patch.isBridge()});
    if (print)
      fmt::print("      root s={:.9g} {}{}\n", s, patch.isBridge() ? "bridge" : "patch",
                 why.empty() ? " KEPT" : why);
  }
  return notes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    fmt::print(stderr, "usage: crack_probe MESH [--lines N] [--seed S] [--normals NAME]\n");
    return 2;
  }
  std::string spec = argv[1], normals = "average";
  size_t lines = 100000, show = 10;
  uint64_t seed = 1;
  double strayFactor = 1.0;
  std::vector<size_t> dump;
  for (int i = 2; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--dump") dump.push_back(std::stoull(value));
    if (key == "--lines") lines = std::stoull(value);
    if (key == "--seed") seed = std::stoull(value);
    if (key == "--normals") normals = value;
    if (key == "--show") show = std::stoull(value);
    if (key == "--stray") strayFactor = std::stod(value);
  }
  BuiltinMesh input = loadMeshSpec(spec, parseNormalSource(normals));
  const auto mesh = std::make_shared<const TriangleMesh>(std::move(input.mesh));
  const TriangleMesh& m = *mesh;
  const RobustImplicitModel model(mesh);
  const auto& all = model.renderPatches();
  const size_t patchCount = model.quadricPatches().size();
  fmt::print("{}: {} triangles, {} bridges, {} flat ({:.3f}%), {} blended, {}\n", spec,
             m.triangleCount(), model.bridgeCount(), model.flatCount(),
             100.0 * double(model.flatCount()) / double(m.triangleCount()), model.blendedCount(),
             MeshTopology(m).isClosed() ? "closed" : "open");

  for (size_t t : dump) {
    const QuadricPatch& p = all[t];
    fmt::print("triangle {}: vertices {} {} {}, flat {}, blend {}, orientation {}\n", t,
               m.triangles[t][0], m.triangles[t][1], m.triangles[t][2], model.isFlat(t),
               model.blend(t), p.orientation);
    for (int k = 0; k < 3; ++k) {
      const Vec3 c = m.corner(t, k), n = m.cornerNormal(t, k);
      fmt::print("  corner ({:.9g},{:.9g},{:.9g}) normal ({:.6f},{:.6f},{:.6f})\n", c.x(), c.y(),
                 c.z(), n.x(), n.y(), n.z());
    }
    fmt::print("  q {}\n  base ({:.6g},{:.6g},{:.6g},{:.6g})\n", fmt::join(p.q, " "), p.base[0],
               p.base[1], p.base[2], p.base[3]);
    for (int k = 0; k < p.planeCount; ++k)
      fmt::print("  plane {} ({:.6g},{:.6g},{:.6g},{:.6g})\n", k, p.planes[k][0], p.planes[k][1],
                 p.planes[k][2], p.planes[k][3]);
    fmt::print("  bounds ({:.6g},{:.6g},{:.6g}) ({:.6g},{:.6g},{:.6g})\n", p.bounds.lo.x(),
               p.bounds.lo.y(), p.bounds.lo.z(), p.bounds.hi.x(), p.bounds.hi.y(), p.bounds.hi.z());
  }
  Accel accel(Accel::Options{true, true});
  accel.addQuadricPatches(all);
  accel.commit();
  Bounds3 box = accel.bounds();
  const double diagonal = box.diagonal().norm();
  {
    // Widest gap between the two sides' boundaries along each interior edge (13 samples), in
    // units of the crack rate's merge distance (1e-7 of the diagonal).
    const MeshTopology topo(m);
    const Vec2 cornerUv[3] = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
    size_t histogram[8] = {};
    for (const Edge& edge : topo.edges) {
      if (edge.sides.size() != 2) continue;
      const auto [ta, ka] = edge.sides[0];
      const auto [tb, kb] = edge.sides[1];
      const bool sameWay = m.triangles[ta][ka] == m.triangles[tb][kb];
      double gap = 0;
      for (int j = 0; j <= 12; ++j) {
        const double sa = j / 12.0, sb = sameWay ? sa : 1 - sa;
        const Vec2 ua = cornerUv[ka] + sa * (cornerUv[(ka + 1) % 3] - cornerUv[ka]);
        const Vec2 ub = cornerUv[kb] + sb * (cornerUv[(kb + 1) % 3] - cornerUv[kb]);
        gap = std::max(gap, (model.evaluate(ta, ua.x(), ua.y()).position -
                             model.evaluate(tb, ub.x(), ub.y()).position)
                                .norm());
      }
      const double r = gap / (1e-7 * diagonal);
      int bin = r < 1e-3   ? 0
                : r < 1e-1 ? 1
                : r < 1    ? 2
                : r < 10   ? 3
                : r < 100  ? 4
                : r < 1e3  ? 5
                : r < 1e4  ? 6
                           : 7;
      ++histogram[bin];
    }
    fmt::print(
        "edge gaps / merge distance: <1e-3 {}, <0.1 {}, <1 {}, <10 {}, <100 {}, <1e3 {}, <1e4 {}, "
        "more {}\n",
        histogram[0], histogram[1], histogram[2], histogram[3], histogram[4], histogram[5],
        histogram[6], histogram[7]);
  }
  box.inflate(0.05 * diagonal);
  const double merge = 1e-7 * diagonal;
  const double reach = box.diagonal().norm();

  // The flat triangles, for comparison: lines whose crossings of the mesh itself do not
  // alternate (an inside-out or self-crossing mesh).
  Accel flatAccel(Accel::Options{true, true});
  flatAccel.addTriangles(m);
  flatAccel.commit();
  std::atomic<size_t> flatNonAlternating{0};
  std::vector<size_t> cracked;
  size_t evenByAlternations = 0;
  std::mutex mutex;
  std::atomic<size_t> stray{0}, nonAlternating{0};
  double worstStray = 0;
  size_t worstStrayPrim = 0;
  parallelFor(size_t(0), lines, [&](size_t i) {
    const FlushToZeroScope flushToZero;
    Pcg32 rng(seed, i);
    const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
    const Vec3 p = box.lo + box.diagonal().cwiseProduct(u);
    const Vec3 d = uniformDirection(rng);
    std::vector<RayHit> hits;
    std::vector<Hit> line;
    for (const double sign : {1.0, -1.0}) {
      const size_t before = hits.size();
      accel.allHits(Ray{p, sign * d, 0.0, reach}, hits);
      for (size_t k = before; k < hits.size(); ++k)
        line.push_back(
            {sign * hits[k].t, hits[k].geometricNormal.dot(d) < 0.0, size_t(hits[k].primitive)});
    }
    std::sort(line.begin(), line.end(), [](const Hit& a, const Hit& b) { return a.s < b.s; });
    size_t crossings = 0;
    for (size_t k = 0; k < line.size();) {
      bool mixed = false;
      size_t j = k + 1;
      for (; j < line.size() && line[j].s - line[j - 1].s < merge; ++j)
        mixed |= line[j].entering != line[k].entering;
      crossings += mixed ? 2 : 1;
      k = j;
    }
    for (const Hit& h : line) {
      const QuadricPatch& prim = all[h.primitive];
      const Vec3 x = p + h.s * d;
      double dist = kInfinity, scale = 0;
      std::vector<size_t> tris;
      if (prim.isBridge())
        tris = {size_t(prim.joins[0]), size_t(prim.joins[1])};
      else
        tris = {h.primitive};
      for (size_t t : tris) {
        dist = std::min(dist,
                        pointTriangleDistance(x, m.corner(t, 0), m.corner(t, 1), m.corner(t, 2)));
        scale = std::max(scale, m.meanEdgeLength(t));
      }
      if (dist > strayFactor * scale) {
        ++stray;
        std::lock_guard lock(mutex);
        if (dist / scale > worstStray) {
          worstStray = dist / scale;
          worstStrayPrim = h.primitive;
        }
      }
    }
    // The same clusters counted by their direction changes: runs of hits crossing the same
    // way are one crossing (a shared boundary), and each change of direction is another.
    size_t alternations = 0;
    for (size_t k = 0; k < line.size();) {
      size_t j = k + 1, count = 1;
      for (; j < line.size() && line[j].s - line[j - 1].s < merge; ++j)
        count += line[j].entering != line[j - 1].entering;
      alternations += count;
      k = j;
    }
    {
      std::vector<RayHit> flatHits;
      std::vector<std::pair<double, bool>> flatLine;
      for (const double sign : {1.0, -1.0}) {
        flatHits.clear();
        flatAccel.allHits(Ray{p, sign * d, 0.0, reach}, flatHits);
        for (const RayHit& h : flatHits)
          flatLine.emplace_back(sign * h.t, h.geometricNormal.dot(d) < 0.0);
      }
      std::sort(flatLine.begin(), flatLine.end());
      bool alternate = true;
      int last = 0;
      for (size_t k = 0; k < flatLine.size(); ++k) {
        if (k > 0 && flatLine[k].first - flatLine[k - 1].first < merge &&
            flatLine[k].second == flatLine[k - 1].second)
          continue;
        const int dir = flatLine[k].second ? 1 : -1;
        alternate &= last == 0 || dir != last;
        last = dir;
      }
      if (!alternate) ++flatNonAlternating;
    }
    // Whether the crossings, duplicates within the merge distance collapsed, alternate
    // between entering and leaving (a surface that bounds a solid without crossing itself,
    // either way out).
    {
      bool alternate = true;
      int last = 0;  // +1 entering, -1 leaving
      for (size_t k = 0; k < line.size(); ++k) {
        if (k > 0 && line[k].s - line[k - 1].s < merge && line[k].entering == line[k - 1].entering)
          continue;
        const int dir = line[k].entering ? 1 : -1;
        alternate &= last == 0 || dir != last;
        last = dir;
      }
      if (!alternate) ++nonAlternating;
    }
    if (crossings % 2 == 1) {
      std::lock_guard lock(mutex);
      cracked.push_back(i);
      if (alternations % 2 == 0) ++evenByAlternations;
    }
  });
  std::sort(cracked.begin(), cracked.end());
  fmt::print(
      "lines whose crossings do not alternate between entering and leaving: {} (flat "
      "triangles: {})\n",
      nonAlternating.load(), flatNonAlternating.load());
  fmt::print(
      "cracked lines whose hits, counted by direction changes within the merge distance, "
      "are even: {}\n",
      evenByAlternations);
  fmt::print(
      "cracked {} of {} lines ({:.3g}); stray hits (> {} edge lengths): {}, worst {:.3g} "
      "(primitive {})\n",
      cracked.size(), lines, double(cracked.size()) / double(lines), strayFactor, stray.load(),
      worstStray, worstStrayPrim);

  // Per cracked line: the model's and the triangles' crossings, and the first disagreement.
  std::map<std::string, size_t> featureCounts;
  size_t shown = 0;
  for (size_t i : cracked) {
    Pcg32 rng(seed, i);
    const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
    const Vec3 p = box.lo + box.diagonal().cwiseProduct(u);
    const Vec3 d = uniformDirection(rng);
    std::vector<RayHit> hits;
    std::vector<Hit> line;
    for (const double sign : {1.0, -1.0}) {
      const size_t before = hits.size();
      accel.allHits(Ray{p, sign * d, 0.0, reach}, hits);
      for (size_t k = before; k < hits.size(); ++k)
        line.push_back(
            {sign * hits[k].t, hits[k].geometricNormal.dot(d) < 0.0, size_t(hits[k].primitive)});
    }
    std::sort(line.begin(), line.end(), [](const Hit& a, const Hit& b) { return a.s < b.s; });
    struct TriHit {
      double s;
      size_t t;
      Vec3 bary;
      bool entering;
    };
    std::vector<TriHit> tri;
    for (size_t t = 0; t < m.triangleCount(); ++t) {
      TriHit h;
      if (lineTriangle(m, t, p, d, h.s, h.bary, h.entering)) {
        h.t = t;
        tri.push_back(h);
      }
    }
    std::sort(tri.begin(), tri.end(), [](const TriHit& a, const TriHit& b) { return a.s < b.s; });
    // Walk both sequences by parity: the first triangle crossing after which the model's
    // inside/outside differs from the triangles' for good.
    // Simple heuristic: pair each triangle crossing with the nearest unused model hit of the
    // same direction within 0.5 mean edge lengths; report unpaired ones.
    std::vector<char> used(line.size(), 0);
    std::vector<size_t> unpairedTri;
    for (size_t k = 0; k < tri.size(); ++k) {
      const double scale = m.meanEdgeLength(tri[k].t);
      double best = 0.5 * scale;
      int bestJ = -1;
      for (size_t j = 0; j < line.size(); ++j)
        if (!used[j] && line[j].entering == tri[k].entering &&
            std::abs(line[j].s - tri[k].s) < best) {
          best = std::abs(line[j].s - tri[k].s);
          bestJ = int(j);
        }
      if (bestJ < 0) {
        unpairedTri.push_back(k);
      } else {
        used[size_t(bestJ)] = 1;
        // Absorb same-direction model hits merged with it.
        for (size_t j = 0; j < line.size(); ++j)
          if (!used[j] && line[j].entering == tri[k].entering &&
              std::abs(line[j].s - line[size_t(bestJ)].s) < merge)
            used[j] = 1;
      }
    }
    std::vector<size_t> unpairedModel;
    for (size_t j = 0; j < line.size(); ++j)
      if (!used[j]) unpairedModel.push_back(j);
    // The location: the first unpaired triangle crossing, else the first unpaired model hit.
    std::string feature = "unlocated";
    Vec3 where = p;
    size_t whereTri = 0;
    bool located = false;
    if (!unpairedTri.empty()) {
      const TriHit& h = tri[unpairedTri.front()];
      where = p + h.s * d;
      whereTri = h.t;
      located = true;
      feature = "hole";
    } else if (!unpairedModel.empty()) {
      const Hit& h = line[unpairedModel.front()];
      where = p + h.s * d;
      const QuadricPatch& prim = all[h.primitive];
      whereTri = prim.isBridge() ? size_t(prim.joins[0]) : h.primitive;
      located = true;
      feature = prim.isBridge() ? "extra-bridge-hit" : "extra-patch-hit";
    }
    if (located) {
      // Nearest feature of triangle whereTri (barycentrics of the projection).
      const Vec3 a = m.corner(whereTri, 0), b = m.corner(whereTri, 1), c = m.corner(whereTri, 2);
      const Vec3 n = (b - a).cross(c - a);
      const Vec3 q = where - n.dot(where - a) / n.squaredNorm() * n;
      const double wb = (q - a).cross(c - a).dot(n) / n.squaredNorm();
      const double wc = (b - a).cross(q - a).dot(n) / n.squaredNorm();
      const double bary[3] = {1 - wb - wc, wb, wc};
      const double scale = m.meanEdgeLength(whereTri);
      int small = 0;
      for (double w : bary) small += w < 0.05;
      const bool anyFlat = model.isFlat(whereTri);
      feature += small >= 2 ? "@vertex" : small == 1 ? "@edge" : "@face";
      feature += anyFlat ? "+flat" : "";
      (void)scale;
    }
    // Every primitive touching whereTri's vertices, and their roots near `where`.
    const double scale = located ? m.meanEdgeLength(whereTri) : 0.0;
    const double sw = (where - p).dot(d);
    std::vector<size_t> nearby;
    if (located) {
      for (size_t t = 0; t < patchCount; ++t)
        for (uint32_t v : m.triangles[t])
          for (uint32_t w : m.triangles[whereTri])
            if (v == w) nearby.push_back(t);
      std::sort(nearby.begin(), nearby.end());
      nearby.erase(std::unique(nearby.begin(), nearby.end()), nearby.end());
      for (size_t j = patchCount; j < all.size(); ++j)
        if (std::binary_search(nearby.begin(), nearby.end(), size_t(all[j].joins[0])) ||
            std::binary_search(nearby.begin(), nearby.end(), size_t(all[j].joins[1])))
          nearby.push_back(j);
    }
    std::string cause;
    if (located && feature.rfind("hole", 0) == 0) {
      // The dropped root nearest the hole with the fewest reasons.
      size_t fewest = 99;
      double nearest = 0.1 * scale;
      for (size_t j : nearby)
        for (const RootNote& note :
             explainRoots(model, j, p, d, sw - 0.1 * scale, sw + 0.1 * scale, false)) {
          if (note.why.empty()) continue;
          const size_t n = size_t(std::count(note.why.begin(), note.why.end(), ' '));
          const double dist = std::abs(note.s - sw);
          if (n < fewest || (n == fewest && dist < nearest)) {
            fewest = n;
            nearest = dist;
            cause = std::string(note.bridge ? " bridge dropped by" : " patch dropped by") +
                    note.why + (!note.bridge && model.isFlat(j) ? " (flat)" : "");
          }
        }
      if (cause.empty()) cause = " no root near";
    } else if (located) {
      // An extra hit: why its primitive's other root on the line (the partner crossing of
      // the same sheet) was dropped.
      const size_t j = line[unpairedModel.front()].primitive;
      for (const RootNote& note : explainRoots(model, j, p, d, sw - scale, sw + scale, false))
        if (!note.why.empty() && std::abs(note.s - sw) > 1e-12 * scale)
          cause = " partner dropped by" + note.why;
      if (cause.empty()) cause = " no partner root";
      if (!all[j].isBridge() && model.isFlat(j)) cause += " (flat)";
    }
    // For a bridge hit in a cluster of three or more within the merge distance: where along
    // its edge it lies (0 and 1 at the edge's ends) and the gap between the two sides there.
    for (size_t k = 0; k + 2 < line.size(); ++k) {
      if (!(line[k + 2].s - line[k].s < 2 * merge)) continue;
      for (size_t j = k; j < k + 3; ++j) {
        const QuadricPatch& prim = all[line[j].primitive];
        if (!prim.isBridge()) continue;
        const size_t ta = size_t(prim.joins[0]), tb = size_t(prim.joins[1]);
        const int ka = prim.joinPlanes[0];
        const Vec3 a = m.corner(ta, ka), b = m.corner(ta, (ka + 1) % 3);
        const Vec3 x = p + line[j].s * d;
        const double along = (x - a).dot(b - a) / (b - a).squaredNorm();
        fmt::print(
            "triple: line {} bridge ({},{}) at edge parameter {:.4f}, {:.3g} edge lengths "
            "from the nearer end; hits spread {:.3g} merge distances\n",
            i, ta, tb, along, std::min(along, 1 - along), (line[k + 2].s - line[k].s) / merge);
        (void)tb;
      }
    }
    ++featureCounts[feature + cause];
    if (shown >= show) continue;
    ++shown;
    fmt::print("\nline {}: o=({:.9g},{:.9g},{:.9g}) d=({:.9g},{:.9g},{:.9g}) -> {}{}\n", i, p.x(),
               p.y(), p.z(), d.x(), d.y(), d.z(), feature, cause);
    for (size_t j = 0; j < line.size(); ++j) {
      const QuadricPatch& prim = all[line[j].primitive];
      fmt::print("  model s={:.9g} {} {} {}{}\n", line[j].s, line[j].entering ? "in " : "out",
                 prim.isBridge() ? fmt::format("bridge({},{})", prim.joins[0], prim.joins[1])
                                 : fmt::format("patch {}", line[j].primitive),
                 !prim.isBridge() && model.isFlat(line[j].primitive) ? "flat" : "",
                 used[j] ? "" : "  UNPAIRED");
    }
    for (size_t k = 0; k < tri.size(); ++k)
      fmt::print("  tri   s={:.9g} {} tri {} bary ({:.3f},{:.3f},{:.3f}){}{}\n", tri[k].s,
                 tri[k].entering ? "in " : "out", tri[k].t, tri[k].bary[0], tri[k].bary[1],
                 tri[k].bary[2], model.isFlat(tri[k].t) ? " flat" : "",
                 std::find(unpairedTri.begin(), unpairedTri.end(), k) != unpairedTri.end()
                     ? "  UNPAIRED"
                     : "");
    if (located) {
      fmt::print("  near tri {} (vertices {} {} {}), primitives around it:\n", whereTri,
                 m.triangles[whereTri][0], m.triangles[whereTri][1], m.triangles[whereTri][2]);
      for (size_t j : nearby) {
        const QuadricPatch& prim = all[j];
        fmt::print("    {} {}{}\n", j,
                   prim.isBridge() ? fmt::format("bridge({},{})", prim.joins[0], prim.joins[1])
                                   : fmt::format("patch (tri {})", j),
                   !prim.isBridge() && model.isFlat(j) ? " flat" : "");
        explainRoots(model, j, p, d, sw - 0.5 * scale, sw + 0.5 * scale, true);
      }
    }
  }
  fmt::print("\nfeatures of cracked lines:\n");
  std::vector<std::pair<size_t, std::string>> sorted;
  for (const auto& [name, count] : featureCounts) sorted.emplace_back(count, name);
  std::sort(sorted.rbegin(), sorted.rend());
  for (const auto& [count, name] : sorted) fmt::print("  {:7} {}\n", count, name);
  return 0;
}
