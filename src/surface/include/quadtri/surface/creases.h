// Edge curves at creases: what the two triangles of a mesh edge share where their normals are
// split, so every welded model builds the identical boundary curve from both sides
// (docs/DESIGN.md §11).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "quadtri/mesh/triangle_mesh.h"

namespace quadtri {

/// Corner normals at one edge end closer than this (degrees) are merged, not a crease: their
/// cross product would give a crease direction that noise, not geometry, decides.
inline constexpr double kCreaseMinDegrees = 1.0;

/// What every triangle of a mesh edge agrees on at one of its ends.
struct EdgeEnd {
  enum class Kind {
    Shared,  ///< every side carries the same normal there: each side uses its own corner normal
    Merged,  ///< the normals differ by less than kCreaseMinDegrees: `normal`, their unit mean
    Crease,  ///< the normals differ: `direction`, the unit direction of the crease line
  } kind = Kind::Shared;
  Vec3 normal = Vec3::Zero();
  /// n₁ × n₂ normalised for two sides with normals n₁, n₂ (the line both tangent planes
  /// contain); the chord's direction where more than two sides meet or n₁ ≈ −n₂ (a straight
  /// edge). Its sign is arbitrary: everything built from it depends on d d^T only.
  Vec3 direction = Vec3::Zero();

  bool crease() const { return kind == Kind::Crease; }
  /// The unit normal a side uses at this end: `own` (its corner normal) unless Merged.
  const Vec3& normalFor(const Vec3& own) const { return kind == Kind::Merged ? normal : own; }
  /// The chord e from this end projected onto the surface's tangent space there: the tangent
  /// plane e − (e·n)n of unit normal n = normalFor(own), or the crease line (e·d)d.
  Vec3 tangentPart(const Vec3& e, const Vec3& own) const;
};

struct MeshTopology;

/// ends[t][k] = {end at corner k, end at corner k+1} of local edge k of triangle t, computed
/// once per mesh edge from the corner normals of all its sides (compared by value), so both
/// sides read identical data. Stored sparsely: a smooth mesh has no end but Shared ones, so
/// only triangles with another kind of end keep their six ends (4 bytes per triangle besides,
/// where a dense array took 336).
class EdgeEnds {
 public:
  using Triangle = std::array<std::array<EdgeEnd, 2>, 3>;
  /// `triangles` triangles whose ends are all Shared.
  explicit EdgeEnds(size_t triangles = 0) : triangles_(triangles) {}
  const Triangle& operator[](size_t t) const {
    return slot_.empty() || slot_[t] == kShared ? shared() : stored_[slot_[t]];
  }
  size_t size() const { return triangles_; }
  /// True when some end is not Shared (the mesh splits normals along an edge).
  bool anySplit() const { return !stored_.empty(); }

 private:
  friend EdgeEnds edgeEnds(const TriangleMesh&);
  friend EdgeEnds edgeEnds(const TriangleMesh&, const MeshTopology&);
  /// Classifies every edge's ends (edgeEnds without its check for a mesh whose ends are all
  /// Shared).
  static EdgeEnds classify(const TriangleMesh& mesh, const MeshTopology& topo);
  static constexpr uint32_t kShared = ~uint32_t(0);
  static const Triangle& shared() {
    static const Triangle ends{};
    return ends;
  }
  size_t triangles_ = 0;
  std::vector<uint32_t> slot_;  ///< per triangle: its index in stored_, or kShared
  std::vector<Triangle> stored_;
};
EdgeEnds edgeEnds(const TriangleMesh& mesh);
/// Whether edgeEnds(mesh) reads the mesh's edge adjacency (mesh.topology()): only where some
/// vertex's corners carry different normals, or a normal of no length. A smooth mesh's ends are
/// all Shared without it.
bool edgeEndsNeedTopology(const TriangleMesh& mesh);
/// edgeEnds with the mesh's topology already at hand.
EdgeEnds edgeEnds(const TriangleMesh& mesh, const MeshTopology& topo);

/// True when some edge end is not Shared (the mesh splits normals along an edge).
bool hasSplitEdges(const EdgeEnds& ends);

/// Control point b of the quadratic Bézier edge (1−t)² va + 2t(1−t) b + t² vb whose ends are
/// `ea`, `eb` (na, nb: the side's own unit corner normals, used where an end is not a crease),
/// at least one of them a crease. At a crease end the edge's tangent b − v lies on the crease
/// line (b is in both sides' tangent planes), at a smooth end in the tangent plane: b is the
/// least-squares point of those lines and planes (exact where they meet, as the circle tangents
/// of a cylinder's rim do), taken when it lies within half the chord length of the chord's
/// midpoint m and projects onto the chord's middle half (each end tangent keeps at least half
/// the chord's length along the chord). Otherwise (constraints that meet far away or at an end,
/// as where a crease fades into a smooth vertex) b = m + (T_a(e) − T_b(e))/4, e = vb − va,
/// T the tangentPart: the quadratic nearest the cubic Hermite edge whose end tangents are
/// T_a(e) and T_b(e), always within len/2 of m.
/// Symmetric in the two ends bit for bit; a straight crease (a cube's edge) gives m exactly.
Vec3 creaseControlPoint(const Vec3& va, const EdgeEnd& ea, const Vec3& na, const Vec3& vb,
                        const EdgeEnd& eb, const Vec3& nb);

}  // namespace quadtri
