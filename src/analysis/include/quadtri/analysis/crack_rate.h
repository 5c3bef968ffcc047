// Crack rate (docs/DESIGN.md §4): how often a random line crosses a closed surface an odd number of
// times. A watertight surface is crossed an even number of times by every line.
#pragma once

#include <cstddef>
#include <cstdint>

#include "quadtri/geometry/model_geometry.h"

namespace quadtri {

struct CrackRateOptions {
  size_t lines = 100000;
  uint64_t seed = 1;
  /// Lines pass through the geometry's box grown by this fraction of its diagonal on every
  /// side, so that some lines miss the surface or start outside it.
  double boxMargin = 0.05;
};

/// Fraction of `options.lines` random lines crossing `geometry` an odd number of times. Each
/// line passes through a uniform point of the grown box with a uniform direction and is traced
/// both ways in a robust Embree scene that reports every hit. Line i draws from its own PCG32
/// stream, so the result does not depend on the thread count.
///
/// Triangles: Embree's hits are candidates only. Each candidate's vertex one-ring is tested in
/// double precision with edge-side signs (the triple product d·((a−o)×(b−o))) computed once per
/// undirected edge and negated for the opposite direction, so the two triangles of an edge
/// always agree and every line crosses a closed mesh an even number of times: `flat` scores
/// exactly 0. Patches and Bézier pieces: hits closer than 1e-7 × the box diagonal merge when they
/// cross the same way (one crossing through a shared boundary); a cluster that enters and leaves
/// counts twice.
double crackRate(const ModelGeometry& geometry, const CrackRateOptions& options = {});

}  // namespace quadtri
