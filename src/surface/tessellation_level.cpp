// The tessellation spec: parsing it, and the level `auto` picks for a model (the bound on its
// patches' deviation from their flat triangles at level 1).
#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>

#include "quadtri/math/error.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {

Tessellation Tessellation::parse(const std::string& text) {
  if (text == "thesis") return thesis();
  if (text == "auto") return adaptive();
  try {
    if (text.starts_with("auto:")) {
      // from_chars: the same digits in any locale (Python may have set one with a decimal
      // comma), no leading space or sign.
      double tolerance = 0.0;
      const char* first = text.data() + 5;
      const char* last = text.data() + text.size();
      const auto [end, error] = std::from_chars(first, last, tolerance);
      if (error == std::errc() && end == last && std::isfinite(tolerance) && tolerance > 0.0 &&
          tolerance < 1.0)
        return adaptive(tolerance);
    } else {
      size_t used = 0;
      const int level = std::stoi(text, &used);
      if (used == text.size() && level >= 1 && level <= 256) return {Kind::Lattice, level};
    }
  } catch (const std::exception&) {
  }
  fail(
      "tessellation '{}': expected a lattice level from 1 to 256, 'thesis', 'auto' or "
      "'auto:TOLERANCE' (a share of the bounding-box diagonal above 0 and below 1)",
      text);
}

size_t Tessellation::trianglesPerPatch() const {
  if (kind == Kind::Adaptive) return 1;
  return kind == Kind::ThesisGrid ? size_t(2 * (level - 1) * (level - 1)) : size_t(level * level);
}

double levelOneDeviation(const SurfaceModel& model) {
  // The distance e(u, v) between a quadratic patch and the flat triangle through its corners is
  // a quadratic vanishing at the corners, e = uv·A + vw·B + wu·C (w = 1 - u - v): A/4, B/4, C/4
  // at the edges' midpoints, and |e| <= (uv + vw + wu)·max(|A|, |B|, |C|) <= max/3. So 4/3 of
  // the largest midpoint distance bounds it. For the patches of higher degree (PN triangles,
  // the G1 pieces) this is an estimate, to which the centroid and the edges' quarter points add:
  // an S-shaped cubic edge is flat at its midpoint and strays most near a quarter of the way.
  // The corners, the edges' midpoints, the centroid and the edges' quarter points, evaluated in
  // one call a patch (SurfaceModel::positions).
  static const std::array<Vec2, 13> kSamples = {Vec2(0.0, 0.0),
                                                Vec2(1.0, 0.0),
                                                Vec2(0.0, 1.0),
                                                Vec2(0.5, 0.0),
                                                Vec2(0.5, 0.5),
                                                Vec2(0.0, 0.5),
                                                Vec2(1.0 / 3.0, 1.0 / 3.0),
                                                Vec2(0.25, 0.0),
                                                Vec2(0.75, 0.0),
                                                Vec2(0.75, 0.25),
                                                Vec2(0.25, 0.75),
                                                Vec2(0.0, 0.75),
                                                Vec2(0.0, 0.25)};
  const auto patchDeviation = [&](size_t t) {
    std::array<Vec3, kSamples.size()> p;
    model.positions(t, kSamples.data(), kSamples.size(), p.data());
    // A patch whose points are not finite counts as the worst there is (std::max would drop a
    // NaN distance).
    for (const Vec3& point : p)
      if (!allFinite(point)) return kInfinity;
    const auto distance = [&](size_t i) {
      const double u = kSamples[i].x(), v = kSamples[i].y();
      return (p[i] - ((1.0 - u - v) * p[0] + u * p[1] + v * p[2])).norm();
    };
    double midpoints = 0.0, others = 0.0;
    for (size_t i = 3; i < 6; ++i) midpoints = std::max(midpoints, distance(i));
    for (size_t i = 6; i < kSamples.size(); ++i) others = std::max(others, distance(i));
    return std::max(4.0 / 3.0 * midpoints, others);
  };
  return parallelReduce(
      tbb::blocked_range<size_t>(0, model.patchCount(), 1024), 0.0,
      [&](const tbb::blocked_range<size_t>& range, double worst) {
        for (size_t t = range.begin(); t != range.end(); ++t) {
          const double d = patchDeviation(t);
          worst = std::isfinite(d) ? std::max(worst, d) : kInfinity;
        }
        return worst;
      },
      [](double a, double b) { return std::max(a, b); });
}

Tessellation resolveTessellation(const SurfaceModel& model, const Tessellation& tessellation) {
  if (tessellation.kind != Tessellation::Kind::Adaptive) return tessellation;
  const int highest = std::max(1, tessellation.level);
  if (model.representation() == Representation::InputTriangles || model.patchCount() == 0)
    return {Tessellation::Kind::Lattice, 1};
  const Bounds3 box = model.mesh().bounds();
  const double allowed = tessellation.tolerance * (box.hi - box.lo).norm();
  const double deviation = levelOneDeviation(model);
  int level = 1;
  while (level < highest && !(deviation <= allowed * double(level) * double(level))) ++level;
  return {Tessellation::Kind::Lattice, level};
}

Tessellation renderTessellation(const SurfaceModel& model, const Tessellation& tessellation) {
  return model.representation() == Representation::Tessellated
             ? resolveTessellation(model, tessellation)
             : tessellation;
}

}  // namespace quadtri
