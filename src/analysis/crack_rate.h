// Crack rate (DESIGN.md §4): how often a random line crosses a closed surface an odd number of
// times. A watertight surface is crossed an even number of times by every line.
#pragma once

#include <cstddef>
#include <cstdint>

#include "math/vec.h"
#include "render/accel/accel.h"

namespace quadtri {

struct CrackRateOptions {
  size_t lines = 100000;
  uint64_t seed = 1;
  /// Lines pass through the scene's box grown by this fraction of its diagonal on every side,
  /// so that some lines miss the surface or start outside it.
  double boxMargin = 0.05;
};

/// Number of crossings of the line {point + s·direction : |s| < reach} (unit direction),
/// traced both ways from `point`. Hits closer than `mergeDistance` along the line form one
/// cluster: a line through a shared edge or vertex hits every triangle there, and those hits
/// cross the surface in one direction (one crossing); a cluster that both enters and leaves
/// (a line grazing a sharp edge, through a sliver) crosses twice. Entering means d·n < 0 for
/// the hit's oriented geometric normal n. `accel` needs Options::collectHits.
size_t lineCrossings(const Accel& accel, const Vec3& point, const Vec3& direction, double reach,
                     double mergeDistance);

/// Fraction of `options.lines` random lines with an odd crossing count: each line passes
/// through a uniform point of the grown scene box with a uniform direction; hits closer than
/// 1e-7 × the box diagonal merge. Line i draws from its own PCG32 stream, so the result does
/// not depend on the thread count. `accel` must be committed with Options::robust (watertight
/// traversal) and Options::collectHits. Embree's robust test accepts hits up to one float ulp
/// outside an edge, so a line grazing a sharp edge within ~1e-7 of the scene size may report
/// one face of it and not the other: meshes with sharp edges can show false cracks of order
/// 1e-6 (2 of 2,000,000 lines on the tetrahedron); smooth closed meshes measured 0.
double crackRate(const Accel& accel, const CrackRateOptions& options = {});

}  // namespace quadtri
