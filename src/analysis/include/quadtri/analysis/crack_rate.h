// Crack rate (docs/DESIGN.md §4): how often a random line crosses a closed surface an odd number of
// times. A watertight surface is crossed an even number of times by every line.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "quadtri/geometry/model_geometry.h"
#include "quadtri/math/vec.h"

namespace quadtri {

struct CrackRateOptions {
  size_t lines = 100000;
  uint64_t seed = 1;
  /// Lines pass through `lineBox` grown by this fraction of its diagonal on every side, so
  /// that some lines miss the surface or start outside it.
  double boxMargin = 0.05;
  /// The box the lines are drawn through (before the margin); none: the geometry's own box.
  /// Give every model of one mesh the mesh's box, and they are all measured on the same lines:
  /// the geometry's box is the union of its primitives' boxes, which depends on how tightly a
  /// model bounds its patches. Each line is traced through the whole of both boxes. Error for
  /// a box that is inverted, not finite, a single point or beyond what Embree traces.
  std::optional<Bounds3> lineBox;
};

/// Fraction of `options.lines` random lines crossing `geometry` an odd number of times. Each
/// line passes through a uniform point of the grown line box with a uniform direction and is
/// traced both ways in a robust Embree scene that reports every hit. Line i draws from its own
/// PCG32 stream, so the result does not depend on the thread count.
///
/// Triangles: Embree's hits are candidates only. Each candidate's vertex one-ring is tested in
/// double precision with edge-side signs (the triple product d·((a−o)×(b−o))) computed once per
/// undirected edge and negated for the opposite direction, so the two triangles of an edge
/// always agree and every line crosses a closed mesh an even number of times: `flat` scores
/// exactly 0. Patches and Bézier pieces: hits closer than 1e-7 × the box diagonal merge when they
/// cross the same way (one crossing through a shared boundary); a cluster that enters and leaves
/// counts twice.
double crackRate(const ModelGeometry& geometry, const CrackRateOptions& options = {});

/// Crossings of the line o + s·d with `mesh`'s triangles, as crackRate counts them for triangle
/// geometry with Embree's hits as `candidates`: exact edge signs on the vertex one-rings of the
/// candidates and, in turn, of every crossed triangle's vertices (a line through a fold that
/// Embree sees one sheet of still meets the others). Error for a candidate beyond the mesh.
size_t triangleCrossings(const TriangleMesh& mesh, const Vec3& o, const Vec3& d,
                         const std::vector<uint32_t>& candidates);

/// A primitive's hit at signed distance s along a line, whether it enters the surface there, and
/// whether it may be one point of a boundary two primitives share (always, for quadric patches;
/// for Bézier pieces only a hit on its piece's boundary).
struct LineHit {
  double s;
  bool entering;
  bool shared = true;
  /// Vertices of the triangles the primitive stands for (up to two), ~0u where unknown.
  std::array<uint32_t, 6> vertices{~0u, ~0u, ~0u, ~0u, ~0u, ~0u};
  Vec3 point = Vec3::Zero();  ///< where the line meets the primitive
};

/// Crossings of a line with patches or Bézier pieces among its hits (sorted here by s), as
/// crackRate counts them; `positions` are the mesh's vertices that LineHit::vertices index.
///
/// A cluster of hits closer than `mergeDistance` is one place where the line meets the
/// surface. Its hits are too close to order, so only their balance counts: a line through a
/// shared boundary enters every patch there (or a fold, a bridge and its patches enter twice
/// and leave once), which is one crossing; a cluster that enters as often as it leaves touches
/// the surface, which is two.
///
/// Only hits that may lie on a shared boundary join a cluster's balance: an interior hit of a
/// Bézier piece is a crossing of its own however close another is (two sheets of a surface that
/// folds over itself near an edge, where the data bends it sharply, meet a line 1e-8 apart).
/// And a cluster's balance is taken per group of hits every two of which may share a boundary:
/// their triangles share an edge (or are one), or they share one vertex and both hits lie within
/// 10 × `mergeDistance` of it. Primitives of triangles far apart on the mesh share no boundary,
/// so their hits are separate crossings however close (two components of a mesh that pass
/// through each other cross where a line meets both within the merge distance: `bones`); so are
/// two patches around one vertex that a line meets far from it, even where a third patch shares
/// an edge with each.
size_t patchCrossings(std::vector<LineHit>& line, double mergeDistance,
                      const std::vector<Vec3>& positions);

}  // namespace quadtri
