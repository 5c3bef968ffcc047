// Where to put the origin of coordinates for geometry that may lie far from the world origin.
#pragma once

#include "quadtri/math/vec.h"

namespace quadtri {

/// The centre of `box` where the box lies more than 8 of its half extents from the world
/// origin (every coordinate relative to the centre is then at most a seventh of the world
/// one, so as fine or finer) and within 1e15 of it; otherwise the world origin, whose grid of
/// floating-point numbers is finer near 0 than near any other point. The acceleration structure
/// chooses the origin of Embree's float coordinates this way, and quadric-implicit-robust where
/// it builds a far mesh.
inline Vec3 frameOrigin(const Bounds3& box) {
  if (box.empty()) return Vec3::Zero();
  const Vec3 centre = 0.5 * (box.lo + box.hi);
  const double half = 0.5 * (box.hi - box.lo).maxCoeff(), far = centre.cwiseAbs().maxCoeff();
  return far > 8.0 * half && far <= 1e15 ? centre : Vec3::Zero();
}

}  // namespace quadtri
