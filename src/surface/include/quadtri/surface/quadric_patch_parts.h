// The parts rendering traces a long quadric patch as. A patch's box is the only thing Embree
// knows of it, and a sliver lying across the axes (CAD meshes are full of them) has a box many
// times the area of its triangle: most rays that enter the box miss the patch, and every one of
// them costs a callback and a quadratic solve. On the corpus' pinion (1,300 triangles) rays
// entered 20 patch boxes each under `quadric-implicit`. Split into parts whose boxes hug the
// patch, it is only tested by rays that come near it. The same holds for bridges. The exact box
// of a whole patch (tightPatchBounds, which `quadric-implicit` stores) comes from the same
// bounds of a quadric in a convex cell.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"
#include "quadtri/surface/quadric_patch.h"

namespace quadtri {

/// One primitive of a patch geometry: patch (or bridge) `patch`, restricted to its roots inside
/// the box [lo, hi]. The box holds every point of the patch in its part of the patch's box
/// (bounds exact up to rounding, grown by a hair and rounded outward to float), so the parts of
/// a patch together hold all of it, and a root inside two of them is the same root twice.
struct QuadricPatchPart {
  float lo[3], hi[3];
  uint32_t patch;

  Bounds3 bounds() const {
    Bounds3 b;
    b.lo = Vec3(lo[0], lo[1], lo[2]);
    b.hi = Vec3(hi[0], hi[1], hi[2]);
    return b;
  }
};

/// A patch whose box has more than this many times the area of its triangle is split.
inline constexpr double kLongPatchRatio = 32.0;
/// A box is split in two at the middle of its longest side where the two halves' boxes,
/// tightened to the quadric inside them, have together at most this share of its area (the
/// chance that a ray enters a box is proportional to its area).
inline constexpr double kPartSplitGain = 0.7;
/// At most this many halvings: 8 parts to a patch.
inline constexpr int kMaxPartDepth = 3;
/// The mesh's patches are traced as parts only where that leaves the boxes at most this share
/// of their total area.
inline constexpr double kMeshSplitGain = 0.9;

/// The parts that trace `patches`, in patch order, when some patch is split; empty when none is
/// (each patch is then its own primitive, bounded by its box). Patch t < mesh.triangleCount()
/// stands for triangle t, which gives its area, and a bridge is measured against its first
/// patch's triangle; the others, and those whose boxes are not long, are one part each. Each
/// half of a box is tightened to the bounds of the quadric in it and of the polytopes the
/// patch's points lie in: its planes; for a bridge, its plane and the planes of either side but
/// the one it lies in (betweenSheetAndBase).
std::vector<QuadricPatchPart> quadricPatchParts(const std::vector<QuadricPatch>& patches,
                                                const TriangleMesh& mesh);

/// The exact bounds of {q = 0} inside `box`, grown by a hair for rounding and kept inside the
/// box; empty where the quadric does not meet it.
Bounds3 quadricBoundsInBox(const QuadricCoeffs& q, const Bounds3& box);

/// The box of an ordinary patch's points (its quadric inside its planes and its box), exact up
/// to rounding and grown for it as quadricBoundsInBox's. Where the cell the bounds are computed
/// in is thin, or the quadric ill-conditioned there (at the cell's corners or at `onSurface`,
/// points of the quadric the caller has, such as the samples its box was built from), the box of
/// the cell cut by the patch's box instead, which holds the patch whatever its quadric; the
/// patch's own box where the quadric does not meet the cell, or the cell is long, open or not
/// closed: no root may be lost.
Bounds3 tightPatchBounds(const QuadricPatch& patch, std::span<const Vec3> onSurface = {});

}  // namespace quadtri
