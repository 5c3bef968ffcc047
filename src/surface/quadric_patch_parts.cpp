#include "quadtri/surface/quadric_patch_parts.h"

#include <array>
#include <cmath>
#include <optional>
#include <span>

#include "quadtri/math/fixed_vector.h"
#include "quadtri/math/float_round.h"
#include "quadtri/math/parallel.h"
#include "quadtri/surface/robust_cell.h"

namespace quadtri {
namespace {

using PartBoxes = FixedVector<Bounds3, size_t(1) << kMaxPartDepth>;

// The six faces of `box` as planes, unit normals pointing in.
std::array<Vec4, 6> boxFaces(const Bounds3& box) {
  return {Vec4(1, 0, 0, -box.lo.x()), Vec4(-1, 0, 0, box.hi.x()), Vec4(0, 1, 0, -box.lo.y()),
          Vec4(0, -1, 0, box.hi.y()), Vec4(0, 0, 1, -box.lo.z()), Vec4(0, 0, -1, box.hi.z())};
}

// Planes bounding where a primitive's points can lie, besides its box (unit normals, inside
// n·x + d >= 0).
using PlaneList = FixedVector<Vec4, 2 * QuadricPatch::kMaxPlanes + 2>;
// A primitive's points lie in the union of these polytopes (each cut from a box).
using Polytopes = FixedVector<PlaneList, 2>;

// Where primitive i's points can lie: a patch inside its planes. A bridge inside its own planes
// and on its plane (a linear q, taken both ways); where it joins patches with cells
// (joinPlanes), a point of it is between sheet and base on one side, so inside that side's
// planes but the one it lies in (betweenSheetAndBase): one polytope per side.
Polytopes polytopesOf(const std::vector<QuadricPatch>& patches, size_t i) {
  const QuadricPatch& primitive = patches[i];
  PlaneList own;
  for (int k = 0; k < primitive.planeCount; ++k) own.push_back(primitive.planes[size_t(k)]);
  Polytopes out;
  if (!primitive.isBridge()) {
    out.push_back(own);
    return out;
  }
  const QuadricCoeffs& q = primitive.q;
  const Vec3 n(q[6], q[7], q[8]);
  const double length = n.norm();
  const bool linear = q[0] == 0 && q[1] == 0 && q[2] == 0 && q[3] == 0 && q[4] == 0 && q[5] == 0;
  if (linear && length > 0.0 && std::isfinite(length)) {
    const Vec4 plane = Vec4(n.x(), n.y(), n.z(), q[9]) / length;
    own.push_back(plane);
    own.push_back(-plane);
  }
  const auto valid = [&](int32_t join) { return join >= 0 && size_t(join) < patches.size(); };
  if (primitive.joinPlanes[0] < 0 || !valid(primitive.joins[0]) || !valid(primitive.joins[1])) {
    out.push_back(own);
    return out;
  }
  for (int side = 0; side < 2; ++side) {
    const QuadricPatch& patch = patches[size_t(primitive.joins[size_t(side)])];
    PlaneList planes = own;
    for (int k = 0; k < patch.planeCount; ++k)
      if (k != primitive.joinPlanes[size_t(side)]) planes.push_back(patch.planes[size_t(k)]);
    out.push_back(planes);
  }
  return out;
}

// Exact bounds `tight` of a quadric's points inside `box`, grown for the rounding of the bounds
// (1e-9 of the size and distance from the origin, `scale`, and the cell's tolerance) and for
// that of the roots a ray finds: a ray from far away that grazes the surface, or a quadric with
// a small gradient, places its root along the ray less precisely (1e-5 of the patch's size from
// a thousand patch sizes away on the corpus' pinion), and where the surface touches a face of
// the exact box (a sphere's pole) such a root would fall outside it. 1e-3 of the box's side
// keeps those roots, as the sampled box's margin did, at a small share of its area. Kept
// inside `box`.
Bounds3 grownForRoots(Bounds3 tight, const Bounds3& box, double scale, double tolerance) {
  tight.inflate(1e-3 * box.diagonal().maxCoeff() + 1e-9 * scale + tolerance);
  tight.lo = tight.lo.cwiseMax(box.lo);
  tight.hi = tight.hi.cwiseMin(box.hi);
  return tight;
}

// The box of {x in box : inside every plane}: the polytope's vertices, the points where three
// of its planes meet inside all of them. Empty when none is found.
Bounds3 clippedBoxBounds(const PlaneList& bounding, const Bounds3& box) {
  FixedVector<Vec4, PlaneList::capacity() + 6> planes(bounding.begin(), bounding.end());
  for (const Vec4& face : boxFaces(box)) planes.push_back(face);
  const double scale = box.diagonal().maxCoeff() + box.center().cwiseAbs().maxCoeff();
  const double tolerance = 1e-9 * scale;
  Bounds3 out;
  const size_t n = planes.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        Mat3 m;
        m.row(0) = planes[i].head<3>().transpose();
        m.row(1) = planes[j].head<3>().transpose();
        m.row(2) = planes[k].head<3>().transpose();
        const double det = m.determinant();
        if (!(std::abs(det) > 1e-12)) continue;
        const Vec3 x = m.inverse() * Vec3(-planes[i][3], -planes[j][3], -planes[k][3]);
        bool inside = allFinite(x);
        for (size_t l = 0; inside && l < n; ++l)
          inside = planes[l].head<3>().dot(x) + planes[l][3] >= -tolerance;
        if (inside) out.extend(x);
      }
  out.inflate(tolerance);
  return out;
}

// The bounds of a primitive's points inside `half`: of its quadric there, and of the polytopes
// its points lie in, cut from the half. Empty where there are none; the quadric's bounds alone
// where no polytope gave a vertex (none is lost to rounding).
Bounds3 boundsInHalf(const QuadricCoeffs& q, const Polytopes& polytopes, const Bounds3& half) {
  Bounds3 out = quadricBoundsInBox(q, half);
  if (out.empty()) return out;
  Bounds3 cut;
  for (const PlaneList& planes : polytopes) cut.extend(clippedBoxBounds(planes, half));
  if (cut.empty()) return out;
  out.lo = out.lo.cwiseMax(cut.lo);
  out.hi = out.hi.cwiseMin(cut.hi);
  return (out.lo.array() <= out.hi.array()).all() ? out : Bounds3();
}

// Halves `box` while that pays (kPartSplitGain), each half's box tightened to the primitive's
// points in it (boundsInHalf); the leaves go to `out`. Halves that hold none are left out.
void splitBox(const QuadricCoeffs& q, const Polytopes& polytopes, const Bounds3& box, int depth,
              PartBoxes& out) {
  if (depth < kMaxPartDepth) {
    int axis = 0;
    box.diagonal().maxCoeff(&axis);
    const double middle = 0.5 * (box.lo[axis] + box.hi[axis]);
    Bounds3 lower = box, upper = box;
    lower.hi[axis] = middle;
    upper.lo[axis] = middle;
    const Bounds3 a = boundsInHalf(q, polytopes, lower), b = boundsInHalf(q, polytopes, upper);
    if (a.surfaceArea() + b.surfaceArea() <= kPartSplitGain * box.surfaceArea()) {
      if (!a.empty()) splitBox(q, polytopes, a, depth + 1, out);
      if (!b.empty()) splitBox(q, polytopes, b, depth + 1, out);
      return;
    }
  }
  out.push_back(box);
}

QuadricPatchPart partOf(const Bounds3& box, size_t patch) {
  QuadricPatchPart part;
  for (int c = 0; c < 3; ++c) {
    part.lo[c] = floatDown(box.lo[c]);
    part.hi[c] = floatUp(box.hi[c]);
  }
  part.patch = uint32_t(patch);
  return part;
}

}  // namespace

Bounds3 quadricBoundsInBox(const QuadricCoeffs& q, const Bounds3& box) {
  if (box.empty()) return box;
  const Vec3 size = box.diagonal();
  const double scale = size.maxCoeff() + box.center().cwiseAbs().maxCoeff();
  const double tolerance = 1e-10 * scale;
  const ConvexCell cell = makeConvexCell(boxFaces(box), tolerance);
  // A cell the construction could not complete (a box flat to within the tolerance) keeps the
  // whole box: no part of the patch may be lost.
  if (cell.overflowed || cell.empty()) return box;
  Bounds3 tight = quadricBoundsInCell(q, cell);
  if (tight.empty()) return tight;
  if (!allFinite(tight.lo) || !allFinite(tight.hi)) return box;
  tight = grownForRoots(tight, box, scale, tolerance);
  return tight;
}

namespace {

// A direction r != 0 with n_i·r >= 0 for every plane i, along which {x : n_i·x + d_i >= 0}
// is unbounded whatever the d_i; none where the set is bounded. Such a direction, where one
// exists, can be taken on the line where two of the planes' normals are both orthogonal to it
// (an extreme ray of the recession cone, or its lineality), so the pairs' cross products are
// the only candidates. Directions within rounding of the cone count as in it, with room for
// the pairs whose cross products are barely longer than the 1e-9 taken as parallel. Where no
// two normals are independent, one orthogonal to the first.
std::optional<Vec3> unboundedDirection(std::span<const Vec4> planes) {
  bool anyPair = false;
  for (size_t i = 0; i < planes.size(); ++i)
    for (size_t j = i + 1; j < planes.size(); ++j) {
      const Vec3 r = planes[i].head<3>().cross(planes[j].head<3>());
      const double length = r.norm();
      if (!(length > 1e-9)) continue;
      anyPair = true;
      for (const double sign : {1.0, -1.0}) {
        bool inCone = true;
        for (const Vec4& plane : planes)
          inCone = inCone && sign * plane.head<3>().dot(r) >= -3e-9 * length;
        if (inCone) return Vec3(sign * r / length);
      }
    }
  if (anyPair) return std::nullopt;
  Vec3 s, t;
  orthonormalBasis(planes.empty() ? Vec3(Vec3::UnitZ()) : Vec3(planes[0].head<3>().normalized()), s,
                   t);
  return s;
}

// The plane n·x + d >= 0 through the box's highest point along -n: the box lies inside it.
Vec4 planeHoldingBox(const Vec3& n, const Bounds3& box) {
  const Vec3 lowest(n.x() > 0.0 ? box.lo.x() : box.hi.x(), n.y() > 0.0 ? box.lo.y() : box.hi.y(),
                    n.z() > 0.0 ? box.lo.z() : box.hi.z());
  return Vec4(n.x(), n.y(), n.z(), -n.dot(lowest));
}

// A cell with a vertex farther than this many of the box's sides from the box is long.
constexpr double kLongCell = 1.0;
// A cell narrower than this share of the sampled box's side, across any of its planes, is thin.
constexpr double kThinCell = 0.03;

// True where the cell is a closed polytope as built: at least four faces with polygons, every
// polygon edge a side of exactly two of them and every vertex on at least three. A vertex the
// construction could not place (three planes too near parallel, where a long thin cell ends)
// leaves an edge with one face or a vertex with two, and the exact bounds would then miss the
// part of the cell beyond it.
bool closedCell(const ConvexCell& cell) {
  constexpr size_t kVertices = ConvexCell::kMaxVertices;
  std::array<uint8_t, kVertices * kVertices> sides{};
  std::array<uint8_t, kVertices> faces{};
  size_t polygons = 0;
  for (const ConvexCell::Face& face : cell.faces) {
    if (face.empty()) continue;
    ++polygons;
    for (size_t i = 0; i < face.size(); ++i) {
      const size_t a = size_t(face[i]), b = size_t(face[(i + 1) % face.size()]);
      ++sides[std::min(a, b) * kVertices + std::max(a, b)];
      ++faces[a];
    }
  }
  if (polygons < 4) return false;
  for (size_t v = 0; v < cell.vertices.size(); ++v)
    if (faces[v] < 3) return false;
  for (const uint8_t count : sides)
    if (count != 0 && count != 2) return false;
  return true;
}

}  // namespace

Bounds3 tightPatchBounds(const QuadricPatch& patch, std::span<const Vec3> onSurface) {
  const Bounds3& box = patch.bounds;
  if (box.empty() || patch.planeCount < 1 || patch.planeCount + 2 > int(ConvexCell::kMaxPlanes))
    return box;
  // The patch's points lie inside its planes and its box, so inside its planes and below the
  // box's highest point along the first plane's normal (a cap that holds the whole box, and
  // only one: that plane is already the cell's floor): a cell of at most kMaxPlanes planes (the
  // box's six faces would exceed it) whose quadric's exact bounds, cut by the box, hold them
  // all. Where that cell is unbounded (a flat patch's planes, which all hold its normal, leave
  // it open along the normal), the box's slab along the open direction closes it instead.
  FixedVector<Vec4, ConvexCell::kMaxPlanes> planes;
  for (int k = 0; k < patch.planeCount; ++k) planes.push_back(patch.planes[size_t(k)]);
  planes.push_back(planeHoldingBox(-patch.planes[0].head<3>(), box));
  if (const std::optional<Vec3> open = unboundedDirection(planes)) {
    planes.back() = planeHoldingBox(*open, box);
    planes.push_back(planeHoldingBox(-*open, box));
    if (unboundedDirection(planes)) return box;
  }
  const double side = box.diagonal().maxCoeff();
  const double scale = side + box.center().cwiseAbs().maxCoeff();
  const double tolerance = 1e-10 * scale;
  const ConvexCell cell = makeConvexCell(planes, tolerance);
  if (cell.overflowed || cell.empty() || !closedCell(cell)) return box;
  // A cell reaching far beyond the box (planes nearly parallel: a nearly flat patch's plane (1)
  // and an edge plane that almost holds it) puts its faces' centres, where their conics are
  // set up, far from the patch, and the conics lose the digits that place the patch's points.
  Bounds3 reach = box;
  reach.inflate(kLongCell * side);
  for (const Vec3& v : cell.vertices)
    if (!reach.contains(v)) return box;
  // Where the quadric's own bounds cannot be trusted (below), the cell's: every point of the
  // patch lies inside its planes and its box, so inside the cell and the box, whatever the
  // quadric. No root is lost to it either: a root the ray test keeps passed the same planes and
  // box, and lies in the cell up to the rounding of the cell's corners, far below the margin.
  const auto cellBounds = [&] {
    Bounds3 corners;
    for (const Vec3& v : cell.vertices) corners.extend(v);
    corners = grownForRoots(corners, box, scale, tolerance);
    // A cell that misses the box by more than the margin: the box, as below.
    return (corners.lo.array() <= corners.hi.array()).all() ? corners : box;
  };
  // A thin cell (a nearly flat patch between its plane (1) and an edge plane that almost holds
  // it, or a sliver) has faces the quadric nearly contains, whose conics are ill-conditioned;
  // such a cell is as tight as the patch across it, and on a fine mesh nearly every cell is one.
  for (const Vec4& plane : cell.planes) {
    double width = 0.0;
    for (const Vec3& v : cell.vertices) width = std::max(width, plane.head<3>().dot(v) + plane[3]);
    if (width < kThinCell * side) return cellBounds();
  }
  // A quadric whose zero set double precision places only roughly (a small gradient against
  // large terms), or that is nearly singular over the cell (its gradient small against its
  // second derivatives across the cell: a cone's apex, or a sliver's ill-conditioned fit): its
  // roots along a ray scatter by more than the margin, and its exact bounds say little.
  const double curvature = quadraticPart(patch.q).norm() * side;
  const auto illConditioned = [&](const Vec3& v, double gradient) {
    return quadricRootError(patch.q, v, gradient) > 1e-10 * side || !(1e3 * gradient >= curvature);
  };
  // The gradient's length at each corner of the cell, for this test and the faces' below.
  std::array<double, ConvexCell::kMaxVertices> gradients;
  for (size_t i = 0; i < cell.vertices.size(); ++i) {
    gradients[i] = quadricGradient(patch.q, cell.vertices[i]).norm();
    if (illConditioned(cell.vertices[i], gradients[i])) return cellBounds();
  }
  for (const Vec3& v : onSurface)
    if (illConditioned(v, quadricGradient(patch.q, v).norm())) return cellBounds();
  Bounds3 tight = quadricBoundsInCell(patch.q, cell);
  // A face the quadric all but contains (a nearly flat patch against its triangle's plane):
  // where q vanishes along a whole edge its zeros there are not isolated points, so the face's
  // corners stand for them.
  for (const ConvexCell::Face& face : cell.faces) {
    bool vanishes = !face.empty();
    for (size_t i = 0; vanishes && i < face.size(); ++i) {
      const size_t v = size_t(face[i]);
      vanishes = std::abs(evalQuadric(patch.q, cell.vertices[v])) <= 1e-9 * gradients[v] * side;
    }
    if (vanishes)
      for (const int8_t v : face) tight.extend(cell.vertices[size_t(v)]);
  }
  // No point of the quadric in the cell: keep the box, lest rounding lose a root.
  if (tight.empty() || !allFinite(tight.lo) || !allFinite(tight.hi)) return box;
  tight = grownForRoots(tight, box, scale, tolerance);
  return (tight.lo.array() <= tight.hi.array()).all() ? tight : box;
}

std::vector<QuadricPatchPart> quadricPatchParts(const std::vector<QuadricPatch>& patches,
                                                const TriangleMesh& mesh) {
  const size_t n = patches.size(), triangles = mesh.triangleCount();
  // The long patches, found in parallel; most meshes have few or none, and then nothing more
  // is computed or stored.
  std::vector<uint32_t> longPatches;
  {
    std::vector<uint8_t> isLong(n, 0);
    const size_t count = parallelReduce(
        tbb::blocked_range<size_t>(0, n, 4096), size_t(0),
        [&](const tbb::blocked_range<size_t>& range, size_t found) {
          for (size_t i = range.begin(); i != range.end(); ++i) {
            // A bridge against the triangle of its first patch.
            const size_t t = patches[i].isBridge() ? size_t(patches[i].joins[0]) : i;
            if (t >= triangles) continue;
            const double area = 0.5 * mesh.faceCross(t).norm();
            isLong[i] = patches[i].bounds.surfaceArea() > kLongPatchRatio * area;
            found += isLong[i];
          }
          return found;
        },
        [](size_t a, size_t b) { return a + b; });
    if (count == 0) return {};
    longPatches.reserve(count);
    for (size_t i = 0; i < n; ++i)
      if (isLong[i]) longPatches.push_back(uint32_t(i));
  }
  std::vector<PartBoxes> boxes(longPatches.size());
  parallelFor(size_t(0), longPatches.size(), [&](size_t i) {
    const QuadricPatch& patch = patches[longPatches[i]];
    splitBox(patch.q, polytopesOf(patches, longPatches[i]), patch.bounds, 0, boxes[i]);
    // A quadric that meets no half of its box has no point the patch could show; keep the box
    // all the same, so that rounding cannot take a root away.
    if (boxes[i].empty()) boxes[i].push_back(patch.bounds);
  });
  size_t total = n - longPatches.size();
  for (const PartBoxes& b : boxes) total += b.size();
  // The boxes' total area, whole and split: what a ray's callbacks are in proportion to. A part
  // costs a little more to test than a whole patch (its box is read and checked too), so a
  // split that takes off less than kMeshSplitGain traces the patches whole.
  const double whole = parallelReduce(
      tbb::blocked_range<size_t>(0, n, 4096), 0.0,
      [&](const tbb::blocked_range<size_t>& range, double sum) {
        for (size_t i = range.begin(); i != range.end(); ++i)
          sum += patches[i].bounds.surfaceArea();
        return sum;
      },
      [](double a, double b) { return a + b; });
  double saved = 0.0;
  for (size_t i = 0; i < longPatches.size(); ++i) {
    saved += patches[longPatches[i]].bounds.surfaceArea();
    for (const Bounds3& box : boxes[i]) saved -= box.surfaceArea();
  }
  if (total == n || !(saved > (1.0 - kMeshSplitGain) * whole)) return {};
  std::vector<QuadricPatchPart> parts;
  parts.reserve(total);
  size_t next = 0;
  for (size_t t = 0; t < n; ++t) {
    if (next < longPatches.size() && longPatches[next] == t) {
      for (const Bounds3& box : boxes[next]) parts.push_back(partOf(box, t));
      ++next;
    } else {
      parts.push_back(partOf(patches[t].bounds, t));
    }
  }
  return parts;
}

}  // namespace quadtri
