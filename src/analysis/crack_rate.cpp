#include "analysis/crack_rate.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <functional>
#include <vector>

#include "math/error.h"
#include "render/sampling/rng.h"

namespace quadtri {
namespace {

// A hit at signed distance s along the line, and whether it enters the surface there.
struct LineHit {
  double s;
  bool entering;
};

Vec3 uniformDirection(Pcg32& rng) {
  const double z = 1.0 - 2.0 * rng.nextDouble();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = 2.0 * kPi * rng.nextDouble();
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace

size_t lineCrossings(const Accel& accel, const Vec3& point, const Vec3& direction, double reach,
                     double mergeDistance) {
  // Every hit, not repeated nearest hits: two hits a rounding error apart may come back in
  // either order, and stepping past the first would lose the second.
  std::vector<RayHit> hits;
  std::vector<LineHit> line;
  for (const double sign : {1.0, -1.0}) {
    hits.clear();
    accel.allHits(Ray{point, sign * direction, 0.0, reach}, hits);
    for (const RayHit& h : hits)
      line.push_back({sign * h.t, h.geometricNormal.dot(direction) < 0.0});
  }
  std::sort(line.begin(), line.end(), [](const LineHit& a, const LineHit& b) { return a.s < b.s; });
  size_t crossings = 0;
  for (size_t i = 0; i < line.size();) {
    bool mixed = false;
    size_t j = i + 1;
    for (; j < line.size() && line[j].s - line[j - 1].s < mergeDistance; ++j)
      mixed |= line[j].entering != line[i].entering;
    crossings += mixed ? 2 : 1;
    i = j;
  }
  return crossings;
}

double crackRate(const Accel& accel, const CrackRateOptions& options) {
  if (!accel.robust()) fail("crack rate: the acceleration structure must be built in robust mode");
  if (options.lines == 0) fail("crack rate: the number of lines must be positive");
  Bounds3 box = accel.bounds();
  if (box.empty()) fail("crack rate: the scene is empty");
  const double diagonal = box.diagonal().norm();
  box.inflate(options.boxMargin * diagonal);
  const double mergeDistance = 1e-7 * diagonal;
  // From a point of the grown box, the whole box lies within its diagonal.
  const double reach = box.diagonal().norm();
  const size_t cracked = tbb::parallel_reduce(
      tbb::blocked_range<size_t>(0, options.lines), size_t(0),
      [&](const tbb::blocked_range<size_t>& range, size_t count) {
        enableFlushToZero();
        for (size_t i = range.begin(); i != range.end(); ++i) {
          Pcg32 rng(options.seed, i);
          const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
          const Vec3 p = box.lo + box.diagonal().cwiseProduct(u);
          count += lineCrossings(accel, p, uniformDirection(rng), reach, mergeDistance) % 2;
        }
        return count;
      },
      std::plus<size_t>());
  return double(cracked) / double(options.lines);
}

}  // namespace quadtri
