// Cost of tracing quartic Bézier pieces directly (bezier_intersect.h): one ray–piece test on
// random rays through the piece's box (nearest hit, and every hit), and one ray through the
// Accel on a closed surface of 32 curved pieces.
//
//   quadtri_bench --benchmark_filter=Bezier
#include <benchmark/benchmark.h>

#include <vector>

#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/surface/bezier_intersect.h"

namespace {

using namespace quadtri;

Vec3 direction(Pcg32& rng) {
  const double z = 1.0 - 2.0 * rng.nextDouble(), phi = 2.0 * kPi * rng.nextDouble();
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return Vec3(r * std::cos(phi), r * std::sin(phi), z);
}

// A degree-elevated triangle with every control point's z moved by up to ±amplitude.
BezierTriangle bumpy(const Vec3& a, const Vec3& b, const Vec3& c, double amplitude, Pcg32& rng) {
  BezierTriangle piece;
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j + k <= 4; ++j) {
      Vec3 p = (double(4 - j - k) * a + double(j) * b + double(k) * c) / 4.0;
      p.z() += amplitude * (2.0 * rng.nextDouble() - 1.0);
      piece.b[size_t(BezierTriangle::index(j, k))] = p;
    }
  return piece;
}

struct Rays {
  std::vector<BezierTriangle> pieces;
  std::vector<Ray> rays;
};

// Rays through the box of unit pieces curved by `amplitude` (about two thirds hit).
Rays pieceRays(double amplitude) {
  Pcg32 rng(23);
  Rays r;
  for (int p = 0; p < 16; ++p)
    r.pieces.push_back(bumpy(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), amplitude, rng));
  for (int i = 0; i < 4096; ++i) {
    const Vec3 target(0.5 * rng.nextDouble(), 0.5 * rng.nextDouble(), 0.2 * rng.nextDouble());
    const Vec3 d = direction(rng);
    r.rays.push_back({target - 3.0 * d, d});
  }
  return r;
}

void BezierNearest(benchmark::State& state) {
  const Rays r = pieceRays(double(state.range(0)) / 100.0);
  size_t i = 0, hits = 0;
  for (auto _ : state) {
    const Ray& ray = r.rays[i % r.rays.size()];
    BezierHit hit;
    hits += intersectBezierTriangle(r.pieces[i % r.pieces.size()], ray.origin, ray.direction, 0.0,
                                    kInfinity, hit);
    ++i;
  }
  state.counters["hit"] = double(hits) / double(i);
}
BENCHMARK(BezierNearest)->Arg(5)->Arg(30);

void BezierAll(benchmark::State& state) {
  const Rays r = pieceRays(double(state.range(0)) / 100.0);
  std::vector<BezierHit> hits;
  size_t i = 0;
  for (auto _ : state) {
    const Ray& ray = r.rays[i % r.rays.size()];
    hits.clear();
    intersectBezierTriangleAll(r.pieces[i % r.pieces.size()], ray.origin, ray.direction, 0.0,
                               kInfinity, hits);
    ++i;
  }
}
BENCHMARK(BezierAll)->Arg(5)->Arg(30);

// The octahedron with its faces' control points pushed towards the unit sphere: 8 curved
// pieces meeting exactly, each split into 4 (32 in all), rays at random from outside.
void BezierAccelOctahedron(benchmark::State& state) {
  static const std::vector<BezierTriangle> pieces = [] {
    const Vec3 v[6] = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                       Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    std::vector<BezierTriangle> out;
    for (int sx : {0, 1})
      for (int sy : {2, 3})
        for (int sz : {4, 5}) {
          Vec3 a = v[sx], b = v[sy], c = v[sz];
          if ((b - a).cross(c - a).dot(a + b + c) < 0) std::swap(b, c);
          BezierTriangle piece;
          for (int k = 0; k <= 4; ++k)
            for (int j = 0; j + k <= 4; ++j) {
              const Vec3 p = (double(4 - j - k) * a + double(j) * b + double(k) * c) / 4.0;
              piece.b[size_t(BezierTriangle::index(j, k))] = p * (1.0 + 0.6 * (1.0 - p.norm()));
            }
          for (const BezierTriangle& sub : subdivideBezierTriangle(piece)) out.push_back(sub);
        }
    return out;
  }();
  enableFlushToZero();
  Accel accel;
  accel.addBezierTriangles(pieces);
  accel.commit();
  Pcg32 rng(7);
  std::vector<Ray> rays;
  for (int i = 0; i < 4096; ++i) {
    const Vec3 d = direction(rng);
    rays.push_back({-3.0 * d + 0.9 * direction(rng), d});
  }
  size_t i = 0, hits = 0;
  for (auto _ : state) hits += accel.intersect(rays[i++ % rays.size()]).valid();
  state.counters["hit"] = double(hits) / double(i);
}
BENCHMARK(BezierAccelOctahedron);

}  // namespace
