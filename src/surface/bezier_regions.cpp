// The regions that rendering traces in place of Bézier pieces (bezier_intersect.h:
// BezierSubPatch, bezierSubPatches): each region's record (its box, prism and cone) and the
// budget that splits the pieces into regions, the neediest first. Tracing them is in
// bezier_subpatch.cpp.
#include <tbb/blocked_range.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <mutex>
#include <utility>

#include "bezier_net.h"
#include "quadtri/math/float_round.h"
#include "quadtri/math/large_array.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/bezier_intersect.h"

namespace quadtri {

using namespace bezier_detail;

namespace {

inline void storeFloat(const Vec3& v, float* out) {
  for (int c = 0; c < 3; ++c) out[c] = float(v[c]);
}

// The sub-patch of `net` (the region's own net) with its box, prism and cone. Its directions are
// rounded to float first, and its bounds computed with the rounded ones, then rounded outwards:
// the prism holds the control points exactly for the directions it stores.
BezierSubPatch makeSubPatch(const BezierTriangle& net, uint32_t piece, int depth, const double* cu,
                            const double* cv) {
  BezierSubPatch s;
  s.piece = piece;
  s.depth = uint8_t(depth);
  constexpr double kScale = double(1 << BezierSubPatch::kMaxDepth);
  for (int c = 0; c < 3; ++c)
    s.cu[c] = uint16_t(cu[c] * kScale), s.cv[c] = uint16_t(cv[c] * kScale);
  const Vec3& p0 = net.b[size_t(BezierTriangle::index(0, 0))];
  Bounds3 box;
  for (const Vec3& p : net.b) box.extend(p);
  // Relative to p0: floats keep the box as tight far from the origin as near it.
  for (int c = 0; c < 3; ++c)
    s.lo[c] = floatDown(box.lo[c] - p0[c]), s.hi[c] = floatUp(box.hi[c] - p0[c]);
  const Vec3 e1 = net.b[size_t(BezierTriangle::index(4, 0))] - p0;
  const Vec3 e2 = net.b[size_t(BezierTriangle::index(0, 4))] - p0;
  const Vec3 normal = e1.cross(e2);
  const double area2 = normal.squaredNorm();
  const double size = std::max({e1.norm(), e2.norm(), (e2 - e1).norm()});
  s.p0 = p0;
  const float inf = std::numeric_limits<float>::infinity();
  // A degenerate corner triangle: no prism (every ray passes) and no cone.
  if (!(area2 > 1e-18 * size * size * size * size) || !std::isfinite(area2)) {
    s.hlo = -inf, s.hhi = inf;
    s.lmin[0] = s.lmin[1] = s.lmin[2] = -inf;
    return s;
  }
  storeFloat(normal / std::sqrt(area2), s.n);
  const double e11 = e1.dot(e1), e12 = e1.dot(e2), e22 = e2.dot(e2);
  storeFloat((e22 * e1 - e12 * e2) / area2, s.g1);
  storeFloat((e11 * e2 - e12 * e1) / area2, s.g2);
  s.inverseSize = float(1.0 / size);
  double hlo = kInfinity, hhi = -kInfinity, l0 = kInfinity, l1 = kInfinity, l2 = kInfinity;
  for (const Vec3& b : net.b) {
    const Vec3 r = b - p0;
    const double h = dotf(r, s.n), a = dotf(r, s.g1), c = dotf(r, s.g2);
    hlo = std::min(hlo, h), hhi = std::max(hhi, h);
    l1 = std::min(l1, a), l2 = std::min(l2, c), l0 = std::min(l0, 1.0 - a - c);
  }
  // Grown far beyond the rounding of these projections and of the net.
  s.hlo = floatDown(hlo - 1e-9 * size), s.hhi = floatUp(hhi + 1e-9 * size);
  s.lmin[0] = floatDown(l0 - 1e-9), s.lmin[1] = floatDown(l1 - 1e-9);
  s.lmin[2] = floatDown(l2 - 1e-9);
  // The cone of the crosses of derivative control vectors: its axis their sum (each weighted by
  // its length, which spares a square root per cross), its half-angle the largest angle to it.
  Vec3 du[10], dv[10];
  int at = 0;
  for (int k = 0; k <= 3; ++k)
    for (int j = 0; j + k <= 3; ++j, ++at) {
      const Vec3& base = net.b[size_t(BezierTriangle::index(j, k))];
      du[at] = net.b[size_t(BezierTriangle::index(j + 1, k))] - base;
      dv[at] = net.b[size_t(BezierTriangle::index(j, k + 1))] - base;
    }
  Vec3 crosses[100];
  double lengths2[100];
  Vec3 axis = Vec3::Zero();
  for (int a = 0; a < 10; ++a)
    for (int b = 0; b < 10; ++b) {
      Vec3& c = crosses[10 * a + b];
      c = du[a].cross(dv[b]);
      lengths2[10 * a + b] = c.squaredNorm();
      if (!(lengths2[10 * a + b] > 0.0)) return s;  // a vanishing cross: no cone
      axis += c;
    }
  storeFloat(safeNormalized(axis, normal / std::sqrt(area2)), s.axis);
  Vec3 stored(s.axis[0], s.axis[1], s.axis[2]);
  stored *= 1.0 / stored.norm();
  // The least cosine², as (c·axis)² / |c|², every cross on the axis' side.
  double cos2Min = 1.0;
  for (int i = 0; i < 100; ++i) {
    const double along = crosses[i].dot(stored);
    if (!(along > 0.0)) return s;
    cos2Min = std::min(cos2Min, along * along / lengths2[i]);
  }
  // The sine of the half-angle, grown far beyond the rounding of these products and of the axis.
  s.sinCone = floatUp(std::sqrt(std::max(0.0, 1.0 - cos2Min)) + 1e-6);
  return s;
}

}  // namespace

Bounds3 BezierSubPatch::bounds() const {
  Bounds3 b;
  b.lo = p0 + Vec3(lo[0], lo[1], lo[2]);
  b.hi = p0 + Vec3(hi[0], hi[1], hi[2]);
  // Grown by a few double ulps of the coordinates: the differences from p0 and the sums were
  // rounded.
  b.inflate(0x1.0p-50 * (b.lo.cwiseAbs().maxCoeff() + b.hi.cwiseAbs().maxCoeff()));
  return b;
}

namespace {

// A region's box holding more than this many times the area of its corner triangle is split.
constexpr double kBoxPerArea = 6.0;
// A corner triangle with (longest side)² / (2·area) above this is bisected across that side
// (an equilateral one has 1.15, a right isosceles one 2).
constexpr double kElongated = 2.5;

double boxArea(const BezierSubPatch& s) {
  const double dx = double(s.hi[0]) - s.lo[0], dy = double(s.hi[1]) - s.lo[1];
  const double dz = double(s.hi[2]) - s.lo[2];
  return 2.0 * (dx * dy + dy * dz + dz * dx);
}

// The corner triangle of a region's net: its corners and area.
struct CornerTriangle {
  Vec3 p[3];
  double area = 0.0;
};

CornerTriangle cornerTriangle(const BezierTriangle& net) {
  CornerTriangle c;
  c.p[0] = net.at(4, 0, 0);
  c.p[1] = net.at(0, 4, 0);
  c.p[2] = net.at(0, 0, 4);
  c.area = 0.5 * (c.p[1] - c.p[0]).cross(c.p[2] - c.p[0]).norm();
  return c;
}

// The most regions a piece can hold: every one 10 bisections deep.
constexpr size_t kMaxRegions = size_t(1) << BezierSubPatch::kMaxDepth;

// A region while the sub-patches are built: its net, its sub-patch and how much it needs a split.
struct Region {
  BezierTriangle net;
  BezierSubPatch sub;
  double coneNeed = 0.0;  // the cone's sine over the largest allowed
  double boxNeed = 0.0;   // an elongated region's box ratio over kBoxPerArea (0 otherwise)
  double need = 0.0;      // the larger: above 1, worth splitting
  int longest = -1;       // the corner opposite the side to bisect; -1: split in 4
};

Region makeRegion(const BezierTriangle& net, uint32_t p, int depth, const double* cu,
                  const double* cv, double sinMax) {
  Region item;
  item.net = net;
  item.sub = makeSubPatch(item.net, p, depth, cu, cv);
  const CornerTriangle c = cornerTriangle(item.net);
  double side2 = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double l2 = (c.p[(k + 2) % 3] - c.p[(k + 1) % 3]).squaredNorm();
    if (l2 > side2) side2 = l2, item.longest = k;
  }
  const double boxRatio = c.area > 0.0 ? boxArea(item.sub) / (2.0 * c.area) : kInfinity;
  if (!(side2 > kElongated * 2.0 * c.area)) item.longest = -1;
  // A box too large for its region shrinks by bisection only: split in 4, a region's children
  // have its shape, and their boxes together its box's area.
  item.coneNeed = double(item.sub.sinCone) / sinMax;
  item.boxNeed = item.longest >= 0 ? boxRatio / kBoxPerArea : 0.0;
  item.need = std::max(item.coneNeed, item.boxNeed);
  return item;
}

// Splits a piece's regions, the neediest first, while fewer than `share`; leaves them in `items`.
// Returns whether some region still needed a split the share left no room for, and sets
// `estimate` to the regions the piece alone would need (1 to kMaxRegions): a cone narrows with
// the region's side, so a 4-split quarters the square of its need; a bisection halves an
// elongated region's box need.
bool splitPiece(const BezierTriangle& piece, uint32_t p, size_t share, double sinMax,
                std::vector<Region>& items, std::vector<size_t>& heap, double& estimate) {
  items.clear();
  heap.clear();
  const double whole[2][3] = {{0, 1, 0}, {0, 0, 1}};
  items.push_back(makeRegion(piece, p, 0, whole[0], whole[1], sinMax));
  estimate = std::clamp(std::max(items[0].coneNeed * items[0].coneNeed, items[0].boxNeed), 1.0,
                        double(kMaxRegions));
  const auto cost = [&](size_t i) { return items[i].longest >= 0 ? 1 : 2; };
  const auto splittable = [&](size_t i) {
    return items[i].sub.depth + cost(i) <= BezierSubPatch::kMaxDepth && items[i].need > 1.0;
  };
  const auto lessNeedy = [&](size_t a, size_t b) {
    return items[a].need < items[b].need || (items[a].need == items[b].need && a > b);
  };
  bool starved = false;
  if (splittable(0)) heap.push_back(0);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end(), lessNeedy);
    const size_t at = heap.back();
    heap.pop_back();
    const int step = cost(at), children = step == 1 ? 2 : 4;
    if (items.size() + size_t(children - 1) > share) {
      starved = true;
      continue;
    }
    const BezierSubPatch parent = items[at].sub;
    double pu[3], pv[3];
    parent.corners(pu, pv);
    // The children's corners in the piece's (u, v), and their nets from the parent's.
    double cu[4][3], cv[4][3];
    std::array<BezierTriangle, 4> nets;
    if (children == 2) {
      // Across the side opposite corner r at its midpoint m: (m, c_r, c_r+1) and
      // (m, c_r+2, c_r), both with the parent's orientation.
      const int r = items[at].longest, r1 = (r + 1) % 3, r2 = (r + 2) % 3;
      const int order[2][3] = {{-1, r, r1}, {-1, r2, r}};
      for (int m = 0; m < 2; ++m)
        for (int c = 0; c < 3; ++c) {
          const int k = order[m][c];
          cu[m][c] = k < 0 ? 0.5 * (pu[r1] + pu[r2]) : pu[k];
          cv[m][c] = k < 0 ? 0.5 * (pv[r1] + pv[r2]) : pv[k];
        }
      const std::array<BezierTriangle, 2> halves = bisectBezierTriangle(items[at].net, r);
      nets[0] = halves[0];
      nets[1] = halves[1];
    } else {
      nets = subdivideBezierTriangle(items[at].net);
      for (int m = 0; m < 4; ++m) {
        std::copy(pu, pu + 3, cu[m]);
        std::copy(pv, pv + 3, cv[m]);
        childCorners(m, cu[m], cv[m]);
      }
    }
    for (int m = 0; m < children; ++m) {
      const size_t slot = m == 0 ? at : items.size();
      Region child =
          makeRegion(nets[size_t(m)], parent.piece, parent.depth + step, cu[m], cv[m], sinMax);
      std::copy(parent.axis, parent.axis + 3, child.sub.parentAxis);
      child.sub.parentSinCone = parent.sinCone;
      std::copy(parent.cu, parent.cu + 3, child.sub.parentU);
      std::copy(parent.cv, parent.cv + 3, child.sub.parentV);
      if (m == 0)
        items[at] = child;
      else
        items.push_back(child);
      if (splittable(slot)) {
        heap.push_back(slot);
        std::push_heap(heap.begin(), heap.end(), lessNeedy);
      }
    }
  }
  return starved;
}

}  // namespace

size_t defaultSubPatchBudget(size_t pieces) {
  return std::max(kMinSubPatchBudget, std::min(kSubPatchesPerPiece * pieces, kMaxSubPatchBudget));
}

std::vector<BezierSubPatch> bezierSubPatches(const std::vector<BezierTriangle>& pieces,
                                             double coneDegrees, size_t budget) {
  if (budget == 0) budget = defaultSubPatchBudget(pieces.size());
  const double sinMax = std::sin(coneDegrees * kPi / 180.0);
  const size_t n = pieces.size();
  if (budget <= n) {
    // No piece's share is more than itself, and nothing is left over (a mesh past the cap):
    // each piece is one region, written in place, without the blocks' buffers, their copy
    // into one array and the per-piece bookkeeping (at 3,000,000 pieces, 500 MB each).
    const double whole[2][3] = {{0, 1, 0}, {0, 0, 1}};
    std::vector<BezierSubPatch> out;
    resizeLarge(out, n);
    parallelFor(size_t(0), n, [&](size_t p) {
      out[p] = makeSubPatch(pieces[p], uint32_t(p), 0, whole[0], whole[1]);
    });
    return out;
  }
  // First an even share of the budget per piece; then what the pieces that needed less left
  // over goes to those that needed more, in proportion to their estimates, and they are split
  // again. Regions are gathered piece after piece and every sum is taken in piece order, so the
  // result does not depend on the threads.
  const size_t even = std::clamp<size_t>(budget / std::max<size_t>(n, 1), 1, kMaxRegions);
  std::vector<size_t> share = largeVector(n, even);
  std::vector<uint16_t> counts = largeVector<uint16_t>(n, 0);
  std::vector<uint8_t> starved = largeVector<uint8_t>(n, 0);
  std::vector<double> estimate = largeVector(n, 0.0);
  // Splits pieces which[0], which[1], ... and returns their regions, piece after piece. A block
  // of pieces appends its regions to a buffer that no other block is using, so the memory held
  // is what the pieces made, not their shares, and it is reused from block to block.
  const auto split = [&](const std::vector<size_t>& which) {
    struct Chunk {
      size_t first, buffer, offset, count;  // which[first...]'s regions in buffers[buffer]
    };
    std::mutex mutex;
    std::deque<std::vector<BezierSubPatch>> buffers;  // stable while others are added
    std::vector<size_t> idle;
    std::vector<Chunk> chunks;
    parallelForRange(
        tbb::blocked_range<size_t>(0, which.size(), 64),
        [&](const tbb::blocked_range<size_t>& range) {
          size_t b;
          std::vector<BezierSubPatch>* held;  // indexed under the lock: others may add buffers
          {
            const std::lock_guard<std::mutex> lock(mutex);
            if (idle.empty()) {
              b = buffers.size();
              buffers.emplace_back();
            } else {
              b = idle.back();
              idle.pop_back();
            }
            held = &buffers[b];
          }
          std::vector<BezierSubPatch>& buffer = *held;
          const size_t offset = buffer.size();
          std::vector<Region> items;
          std::vector<size_t> heap;
          for (size_t i = range.begin(); i != range.end(); ++i) {
            const size_t p = which[i];
            starved[p] =
                splitPiece(pieces[p], uint32_t(p), share[p], sinMax, items, heap, estimate[p]);
            if (buffer.size() + items.size() > buffer.capacity())
              reserveLarge(buffer, std::max(2 * buffer.capacity(), buffer.size() + items.size()));
            for (const Region& item : items) buffer.push_back(item.sub);
            counts[p] = uint16_t(items.size());
          }
          const std::lock_guard<std::mutex> lock(mutex);
          chunks.push_back({range.begin(), b, offset, buffer.size() - offset});
          idle.push_back(b);
        });
    std::sort(chunks.begin(), chunks.end(),
              [](const Chunk& a, const Chunk& b) { return a.first < b.first; });
    size_t total = 0;
    for (const Chunk& c : chunks) total += c.count;
    std::vector<BezierSubPatch> out;
    reserveLarge(out, total);
    for (const Chunk& c : chunks) {
      const auto begin = buffers[c.buffer].begin() + std::ptrdiff_t(c.offset);
      out.insert(out.end(), begin, begin + std::ptrdiff_t(c.count));
    }
    return out;
  };
  std::vector<size_t> all = largeVector<size_t>(n);
  for (size_t p = 0; p < n; ++p) all[p] = p;
  std::vector<BezierSubPatch> firstRegions = split(all);
  std::vector<size_t>().swap(all);
  size_t used = firstRegions.size();
  double weight = 0.0;
  std::vector<size_t> again;
  for (size_t p = 0; p < n; ++p)
    if (starved[p]) again.push_back(p), weight += estimate[p];
  // Only the pieces whose share grows by half at least are split again: each is split from
  // scratch, and a region or two more is not worth that (on the thesis' torus a re-split for
  // every piece given more doubled the build for 1% of the render).
  if (used < budget && weight > 0.0) {
    const double spare = double(budget - used);
    std::vector<size_t> grown;
    for (const size_t p : again) {
      share[p] = std::min(kMaxRegions, even + size_t(spare * estimate[p] / weight));
      if (share[p] < even + std::max<size_t>(1, even / 2)) {
        share[p] = even;
        continue;
      }
      grown.push_back(p);
    }
    again.swap(grown);
  } else {
    again.clear();
  }
  if (again.empty()) return firstRegions;
  // Each piece split again replaces its first regions by its second ones.
  std::vector<uint16_t> firstCounts(counts);
  const std::vector<BezierSubPatch> againRegions = split(again);
  size_t total = 0;
  for (uint16_t c : counts) total += c;
  std::vector<BezierSubPatch> out;
  reserveLarge(out, total);
  size_t nextAgain = 0, fromFirst = 0, fromAgain = 0;
  for (size_t p = 0; p < n; ++p) {
    if (nextAgain < again.size() && again[nextAgain] == p) {
      ++nextAgain;
      const auto begin = againRegions.begin() + std::ptrdiff_t(fromAgain);
      out.insert(out.end(), begin, begin + counts[p]);
      fromAgain += counts[p];
    } else {
      const auto begin = firstRegions.begin() + std::ptrdiff_t(fromFirst);
      out.insert(out.end(), begin, begin + counts[p]);
    }
    fromFirst += firstCounts[p];
  }
  return out;
}

}  // namespace quadtri
