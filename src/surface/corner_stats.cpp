#include "quadtri/surface/corner_stats.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

#include "quadtri/math/parallel.h"
#include "quadtri/surface/creases.h"
#include "quadtri/surface/edge_curves.h"

namespace quadtri {
namespace {

// Barycentric (u, v) of corner k: (0,0), (1,0), (0,1).
const std::array<Vec2, 3> kCornerUv = {Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};

CornerStats join(CornerStats a, const CornerStats& b) {
  a.corners += b.corners;
  a.inconsistent += b.inconsistent;
  a.flips += b.flips;
  a.consistentFlips += b.consistentFlips;
  a.maxNormalErrorDeg = std::max(a.maxNormalErrorDeg, b.maxNormalErrorDeg);
  if (b.maxConsistentNormalErrorDeg)
    a.maxConsistentNormalErrorDeg =
        std::max(a.maxConsistentNormalErrorDeg.value_or(0.0), *b.maxConsistentNormalErrorDeg);
  // The first non-finite corner in patch order, whichever way the range was split.
  if (b.nonFinite && (!a.nonFinite || b.firstNonFinitePatch < a.firstNonFinitePatch)) {
    a.firstNonFinitePatch = b.firstNonFinitePatch;
    a.firstNonFiniteCorner = b.firstNonFiniteCorner;
  }
  a.nonFinite += b.nonFinite;
  return a;
}

// An angle in [0°, 180°] as the argument of atan2: sine >= 0.
struct AngleArg {
  double sine = 0.0, cosine = 1.0;
  // Whether this angle exceeds `other`'s: the sign of the 2D cross product of the (cos, sin)
  // pairs, both in the upper half plane, so no atan2 is needed to compare them. Where it is 0 the
  // angles are equal, or one lies on the axis: 0° or 180° by its cosine's sign bit, as atan2
  // reads it.
  bool wider(const AngleArg& other) const {
    const double cross = sine * other.cosine - cosine * other.sine;
    if (cross != 0.0) return cross > 0.0;
    if (sine == 0.0 && other.sine == 0.0)
      return std::signbit(cosine) && !std::signbit(other.cosine);
    if (other.sine == 0.0) return !std::signbit(other.cosine);
    if (sine == 0.0) return std::signbit(cosine);
    return false;
  }
  // The same value angleDegrees gives for the two vectors.
  double degrees() const { return std::atan2(sine, cosine) * (180.0 / kPi); }
};

// "2.31% of consistent corners (690 of 29868)".
std::string share(size_t part, size_t whole, std::string_view what) {
  return fmt::format("{:.3g}% of {} ({} of {})", 100.0 * double(part) / double(whole), what, part,
                     whole);
}

}  // namespace

bool consistentCorner(const TriangleMesh& mesh, const EdgeEnds& ends, size_t t, int k) {
  return consistentCorner(mesh, ends, t, k, patchOrientation(mesh, t));
}

bool consistentCorner(const TriangleMesh& mesh, const EdgeEnds& ends, size_t t, int k,
                      double orientation) {
  const int next = (k + 1) % 3, prev = (k + 2) % 3;
  const Vec3 p = mesh.corner(t, k);
  const Vec3 n = mesh.cornerNormal(t, k);
  // Local edge k runs k → k+1 and starts here; local edge k+2 runs k+2 → k and ends here.
  const Vec3 t1 = ends[t][k][0].tangentPart(mesh.corner(t, next) - p, n);
  const Vec3 t2 = ends[t][prev][1].tangentPart(mesh.corner(t, prev) - p, n);
  // A crease line that leaves the tangent plane (the chord, where more than two sides meet or
  // the sides' normals are opposite) is no tangent the corner normal can keep.
  for (const EdgeEnd* end : {&ends[t][k][0], &ends[t][prev][1]})
    if (end->crease() && std::abs(end->direction.dot(n)) > 1e-6) return false;
  // Tangents along one line (two edges leaving along the same crease line) span no plane:
  // the sine of their angle must clear round-off.
  return orientation * t1.cross(t2).dot(n) > 1e-9 * t1.norm() * t2.norm();
}

std::optional<double> CornerStats::consistentFlipRate() const {
  if (consistent() == 0) return std::nullopt;
  return double(consistentFlips) / double(consistent());
}

CornerStats cornerStats(const SurfaceModel& model) {
  const TriangleMesh& mesh = model.mesh();
  const EdgeEnds ends = edgeEnds(mesh);
  return parallelReduce(
      tbb::blocked_range<size_t>(0, model.patchCount()), CornerStats(),
      [&](const tbb::blocked_range<size_t>& range, CornerStats s) {
        // The largest angles as (sine, cosine) pairs, |n × n_k| and n · n_k: one atan2 per range
        // instead of one per corner (an eighth of the warning's samples on a million triangles).
        AngleArg worst, worstConsistent;
        bool anyConsistent = false;
        for (size_t t = range.begin(); t != range.end(); ++t) {
          const double orientation = patchOrientation(mesh, t);
          std::array<SurfacePoint, 3> points;
          model.evaluateMany(t, kCornerUv.data(), 3, points.data());
          for (int k = 0; k < 3; ++k) {
            ++s.corners;
            const Vec3 nk = mesh.cornerNormal(t, k);
            const bool consistent = consistentCorner(mesh, ends, t, k, orientation);
            s.inconsistent += !consistent;
            const SurfacePoint& p = points[size_t(k)];
            if (!allFinite(p.position) || !allFinite(p.normal)) {
              if (s.nonFinite++ == 0) {
                s.firstNonFinitePatch = t;
                s.firstNonFiniteCorner = k;
              }
              continue;
            }
            const AngleArg angle{p.normal.cross(nk).norm(), p.normal.dot(nk)};
            const bool flip = angle.cosine < 0.0;
            if (angle.wider(worst)) worst = angle;
            s.flips += flip;
            if (consistent) {
              s.consistentFlips += flip;
              anyConsistent = true;
              if (angle.wider(worstConsistent)) worstConsistent = angle;
            }
          }
        }
        s.maxNormalErrorDeg = std::max(s.maxNormalErrorDeg, worst.degrees());
        if (anyConsistent)
          s.maxConsistentNormalErrorDeg =
              std::max(s.maxConsistentNormalErrorDeg.value_or(0.0), worstConsistent.degrees());
        return s;
      },
      join);
}

double fallbackRate(const SurfaceModel& model) {
  if (model.patchCount() == 0) return 0.0;
  return double(model.fallbackCount()) / double(model.patchCount());
}

std::optional<std::string> conversionWarning(const SurfaceModel& model, std::string_view mesh) {
  // The models that keep the mesh's triangles (flat, shading, shading-offset) have no curved
  // patch to fold and no fallback: nothing to say, and the corner statistics (a fifth of a
  // flat `convert`'s instructions on a 100,000-triangle PLY) are not computed.
  if (model.patchCount() == 0 || model.representation() == Representation::InputTriangles)
    return std::nullopt;
  const CornerStats corners = cornerStats(model);
  const std::optional<double> folds = corners.consistentFlipRate();
  const bool folding = folds && *folds > kConversionWarningRate;
  const bool fallingBack = fallbackRate(model) > kConversionWarningRate;
  if (!folding && !fallingBack) return std::nullopt;
  const std::string foldPart =
      corners.consistent()
          ? "folds at " + share(corners.consistentFlips, corners.consistent(), "consistent corners")
          : std::string("has no consistent corner");
  return fmt::format("{}: {} {} and falls back on {}", mesh, model.name(), foldPart,
                     share(model.fallbackCount(), model.patchCount(), "patches"));
}

}  // namespace quadtri
