#include "quadtri/surface/robust_cell.h"

#include <Eigen/LU>
#include <algorithm>
#include <array>

#include "quadtri/math/error.h"

namespace quadtri {
namespace {

double planeValue(const Vec4& plane, const Vec3& p) {
  return plane.head<3>().dot(p) + plane[3];
}

// Real roots of a s² + b s + c (stable; a linear or constant polynomial gives at most one).
int quadraticRoots(double a, double b, double c, double roots[2]) {
  const double scale = std::abs(a) + std::abs(b) + std::abs(c);
  if (!(scale > 0.0)) return 0;
  if (std::abs(a) <= 1e-14 * scale) {
    if (std::abs(b) <= 1e-300) return 0;
    roots[0] = -c / b;
    return 1;
  }
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return 0;
  const double h = -0.5 * (b + std::copysign(std::sqrt(disc), b));
  if (h == 0.0) {
    roots[0] = 0.0;
    return 1;
  }
  roots[0] = h / a;
  roots[1] = c / h;
  return 2;
}

// Points of the line o + s d where q vanishes.
template <typename Visit>
void lineZeros(const QuadricCoeffs& q, const Vec3& o, const Vec3& d, const Visit& visit) {
  double a, b, c, roots[2];
  quadricAlongLine(q, o, d, a, b, c);
  const int n = quadraticRoots(a, b, c, roots);
  for (int i = 0; i < n; ++i)
    if (std::isfinite(roots[i])) visit(o + roots[i] * d, roots[i]);
}

// A function of the angle of (x, y) that increases with it as atan2(y, x) does on (−π, π], in
// (−2, 2], without a transcendental call: y / (|x| + |y|) on the right half, reflected on the
// left. Enough to sort points around a centre.
double pseudoAngle(double x, double y) {
  const double sum = std::abs(x) + std::abs(y);
  if (!(sum > 0.0)) return 0.0;
  const double r = y / sum;
  if (x >= 0.0) return r;
  return y >= 0.0 ? 2.0 - r : -2.0 - r;
}

// Orthonormal (u, w) spanning the plane with normal n.
void planeBasis(const Vec4& plane, Vec3& u, Vec3& w) {
  orthonormalBasis(plane.head<3>().normalized(), u, w);
}

// The conic in which q meets a plane, as Q(s, r) = A s² + B s r + C r² + D s + E r + F on
// o + s u + r w, (u, w) an orthonormal basis of the plane: computed once per face, whatever the
// number of directions its extremes are asked along.
struct FaceConic {
  Vec3 o, u, w;
  double A, B, C, D, E;

  FaceConic(const QuadricCoeffs& q, const Vec4& plane, const Vec3& origin) : o(origin) {
    planeBasis(plane, u, w);
    const Mat3 M = quadraticPart(q);
    const Vec3 g = quadricGradient(q, o);
    A = u.dot(M * u);
    B = 2.0 * u.dot(M * w);
    C = w.dot(M * w);
    D = g.dot(u);
    E = g.dot(w);
  }

  // Points of the conic where dir·x is extremal along it (the conic's gradient in the face is
  // parallel to dir's projection onto the face).
  template <typename Visit>
  void extremes(const QuadricCoeffs& q, const Vec3& dir, const Visit& visit) const {
    const double alpha = u.dot(dir), beta = w.dot(dir);
    if (!(std::abs(alpha) + std::abs(beta) > 1e-12)) return;  // dir is normal to the face
    // ∇Q × (α, β) = 0: L1 s + L2 r + L0 = 0.
    const double L1 = 2.0 * A * beta - B * alpha, L2 = B * beta - 2.0 * C * alpha;
    const double L0 = D * beta - E * alpha;
    const double norm2 = L1 * L1 + L2 * L2;
    const double size = std::abs(A) + std::abs(B) + std::abs(C);
    if (!(norm2 > 1e-24 * size * size) || !(norm2 > 0.0)) return;
    const Vec3 start = o - (L0 / norm2) * (L1 * u + L2 * w);
    const Vec3 along = (-L2 * u + L1 * w) / std::sqrt(norm2);
    lineZeros(q, start, along, [&](const Vec3& p, double) { visit(p); });
  }
};

// The polygon edges of face f (consecutive vertex pairs).
template <typename Visit>
void faceEdges(const ConvexCell& cell, int f, const Visit& visit) {
  const ConvexCell::Face& face = cell.faces[size_t(f)];
  for (size_t i = 0; i < face.size(); ++i)
    visit(cell.vertices[size_t(face[i])], cell.vertices[size_t(face[(i + 1) % face.size()])]);
}

// Where q vanishes on the segment p0 p1.
template <typename Visit>
void segmentZeros(const QuadricCoeffs& q, const Vec3& p0, const Vec3& p1, const Visit& visit) {
  lineZeros(q, p0, p1 - p0, [&](const Vec3& p, double s) {
    if (s >= -1e-9 && s <= 1.0 + 1e-9) visit(p);
  });
}

Vec3 faceCentre(const ConvexCell& cell, int f) {
  Vec3 c = Vec3::Zero();
  for (int i : cell.faces[size_t(f)]) c += cell.vertices[size_t(i)];
  return c / double(cell.faces[size_t(f)].size());
}

}  // namespace

void quadricAlongLine(const QuadricCoeffs& q, const Vec3& o, const Vec3& d, double& a, double& b,
                      double& c) {
  a = q[0] * d.x() * d.x() + q[1] * d.y() * d.y() + q[2] * d.z() * d.z() + q[3] * d.x() * d.y() +
      q[4] * d.x() * d.z() + q[5] * d.y() * d.z();
  b = quadricGradient(q, o).dot(d);
  c = evalQuadric(q, o);
}

bool ConvexCell::contains(const Vec3& p) const {
  for (const Vec4& plane : planes)
    if (planeValue(plane, p) < -tolerance) return false;
  return true;
}

Bounds3 ConvexCell::bounds() const {
  Bounds3 b;
  for (const Vec3& v : vertices) b.extend(v);
  return b;
}

ConvexCell makeConvexCell(std::span<const Vec4> planes, double tolerance) {
  ConvexCell cell;
  if (planes.size() > ConvexCell::kMaxPlanes)
    fail("a convex cell of {} planes, expected at most {}", planes.size(), ConvexCell::kMaxPlanes);
  cell.planes.assign(planes.begin(), planes.end());
  cell.tolerance = tolerance;
  const size_t n = planes.size();
  const double merge2 = 16.0 * tolerance * tolerance;  // vertices within 4 tolerances are one
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j) {
      const Vec3 ni = planes[i].head<3>(), nj = planes[j].head<3>();
      const Vec3 ij = ni.cross(nj);
      for (size_t k = j + 1; k < n; ++k) {
        // The point on all three planes, by Cramer's rule: with det = n_i·(n_j × n_k),
        // p = −(d_i (n_j × n_k) + d_j (n_k × n_i) + d_k (n_i × n_j)) / det.
        const Vec3 nk = planes[k].head<3>();
        const Vec3 jk = nj.cross(nk);
        const double det = ni.dot(jk);
        if (!(std::abs(det) > 1e-12)) continue;
        const Vec3 p = -(planes[i][3] * jk + planes[j][3] * nk.cross(ni) + planes[k][3] * ij) / det;
        if (!allFinite(p) || !cell.contains(p)) continue;
        bool known = false;
        for (const Vec3& v : cell.vertices) known |= (v - p).squaredNorm() <= merge2;
        if (known) continue;
        if (cell.vertices.full())
          cell.overflowed = true;
        else
          cell.vertices.push_back(p);
      }
    }
  cell.faces.resize(n);
  for (size_t f = 0; f < n; ++f) {
    ConvexCell::Face& face = cell.faces[f];
    for (size_t v = 0; v < cell.vertices.size(); ++v)
      if (std::abs(planeValue(planes[f], cell.vertices[v])) <= 4.0 * tolerance)
        face.push_back(int8_t(v));
    if (face.size() < 3) {
      face.clear();
      continue;
    }
    Vec3 u, w;
    planeBasis(planes[f], u, w);
    Vec3 c = Vec3::Zero();
    for (int v : face) c += cell.vertices[size_t(v)];
    c /= double(face.size());
    // Each vertex's angle about the centre, once (not per comparison).
    std::array<double, ConvexCell::kMaxVertices> angle;
    for (int v : face) {
      const Vec3 p = cell.vertices[size_t(v)] - c;
      angle[v] = pseudoAngle(p.dot(u), p.dot(w));
    }
    std::sort(face.begin(), face.end(), [&](int a, int b) { return angle[a] < angle[b]; });
  }
  return cell;
}

bool cellsOverlap(const ConvexCell& a, const ConvexCell& b, double tolerance) {
  if (a.empty() || b.empty()) return false;
  const auto separated = [&](const Vec3& axis) {
    const double norm = axis.norm();
    if (!(norm > 0.0)) return false;
    double aLo = kInfinity, aHi = -kInfinity, bLo = kInfinity, bHi = -kInfinity;
    for (const Vec3& v : a.vertices) {
      const double x = axis.dot(v) / norm;
      aLo = std::min(aLo, x);
      aHi = std::max(aHi, x);
    }
    for (const Vec3& v : b.vertices) {
      const double x = axis.dot(v) / norm;
      bLo = std::min(bLo, x);
      bHi = std::max(bHi, x);
    }
    return aHi <= bLo + tolerance || bHi <= aLo + tolerance;
  };
  for (const ConvexCell* cell : {&a, &b})
    for (size_t f = 0; f < cell->faces.size(); ++f)
      if (!cell->faces[f].empty() && separated(cell->planes[f].head<3>())) return false;
  const auto edges = [](const ConvexCell& cell) {
    // Each face's polygon edges: at most a vertex's worth per face.
    FixedVector<Vec3, ConvexCell::kMaxPlanes * ConvexCell::kMaxVertices> out;
    for (size_t f = 0; f < cell.faces.size(); ++f)
      faceEdges(cell, int(f), [&](const Vec3& p, const Vec3& q) {
        const Vec3 d = q - p;
        if (d.norm() > 0.0) out.push_back(d.normalized());
      });
    return out;
  };
  const auto ea = edges(a), eb = edges(b);
  for (const Vec3& u : ea)
    for (const Vec3& w : eb) {
      const Vec3 axis = u.cross(w);
      if (axis.norm() > 1e-9 && separated(axis)) return false;
    }
  return true;
}

namespace {

// Every candidate extreme point of dir·x over {q = 0} ∩ cell, for each dir of `dirs`: where the
// surface crosses an edge of the cell, where dir·x is extremal on a face's conic, and inside
// where ∇q ∥ dir.
template <typename Visit>
void extremeCandidates(const QuadricCoeffs& q, const ConvexCell& cell, std::span<const Vec3> dirs,
                       const Visit& visit) {
  const auto keep = [&](const Vec3& p) {
    if (cell.contains(p)) visit(p);
  };
  if (cell.empty()) return;
  // Each edge of the cell is a side of two faces: its zeros are found once, from the first.
  constexpr size_t kVertices = ConvexCell::kMaxVertices;
  std::array<uint64_t, (kVertices * kVertices + 63) / 64> seen{};
  for (size_t f = 0; f < cell.faces.size(); ++f) {
    const ConvexCell::Face& face = cell.faces[f];
    for (size_t i = 0; i < face.size(); ++i) {
      const size_t a = size_t(face[i]), b = size_t(face[(i + 1) % face.size()]);
      const size_t pair = std::min(a, b) * kVertices + std::max(a, b);
      uint64_t& word = seen[pair / 64];
      const uint64_t bit = uint64_t(1) << (pair % 64);
      if (word & bit) continue;
      word |= bit;
      segmentZeros(q, cell.vertices[a], cell.vertices[b], keep);
    }
  }
  for (size_t f = 0; f < cell.faces.size(); ++f) {
    if (cell.faces[f].empty()) continue;
    const Vec3 o = faceCentre(cell, int(f));
    const FaceConic conic(q, cell.planes[f], o);
    for (const Vec3& dir : dirs) conic.extremes(q, dir, keep);
  }
  // Inside: the gradient 2Mx + g has no component along the two directions normal to dir.
  const Mat3 M = quadraticPart(q);
  const Vec3 g(q[6], q[7], q[8]);
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : cell.vertices) centre += v;
  centre /= double(cell.vertices.size());
  for (const Vec3& dir : dirs) {
    Vec3 p1, p2;
    orthonormalBasis(dir.normalized(), p1, p2);
    const Vec3 r1 = 2.0 * M * p1, r2 = 2.0 * M * p2;
    const Vec3 line = r1.cross(r2);
    if (!(line.norm() > 1e-12 * (r1.norm() * r2.norm())) || !(line.norm() > 0.0)) continue;
    Mat3 A;
    A.row(0) = r1;
    A.row(1) = r2;
    A.row(2) = line;
    const Vec3 p = A.inverse() * Vec3(-g.dot(p1), -g.dot(p2), line.dot(centre));
    if (!allFinite(p)) continue;
    lineZeros(q, p, line.normalized(), [&](const Vec3& x, double) { keep(x); });
  }
}

}  // namespace

Bounds3 quadricBoundsInCell(const QuadricCoeffs& q, const ConvexCell& cell) {
  Bounds3 box;
  const std::array<Vec3, 3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  extremeCandidates(q, cell, axes, [&](const Vec3& p) { box.extend(p); });
  return box;
}

std::pair<double, double> quadricRangeInCell(const QuadricCoeffs& q, const ConvexCell& cell,
                                             const Vec3& dir) {
  double lo = kInfinity, hi = -kInfinity;
  extremeCandidates(q, cell, std::span<const Vec3>(&dir, 1), [&](const Vec3& p) {
    lo = std::min(lo, dir.dot(p));
    hi = std::max(hi, dir.dot(p));
  });
  return {lo, hi};
}

Bounds3 betweenBoundsOnFace(const QuadricCoeffs& q, double sign, const Vec4& base,
                            const ConvexCell& cell, int f) {
  Bounds3 box;
  const ConvexCell::Face& face = cell.faces[size_t(f)];
  if (face.empty()) return box;
  const auto between = [&](const Vec3& p) {
    return (sign * evalQuadric(q, p) < 0.0) != (planeValue(base, p) < 0.0);
  };
  const auto keep = [&](const Vec3& p) {
    if (cell.contains(p)) box.extend(p);
  };
  // The region's boundary lies on the conic, on the base line and on the polygon's edges; its
  // extremes are the conic's (axis extremes and crossings of the polygon), the base line's
  // ends on the polygon and the polygon's vertices inside the region.
  for (int v : face)
    if (between(cell.vertices[size_t(v)])) box.extend(cell.vertices[size_t(v)]);
  faceEdges(cell, f, [&](const Vec3& a, const Vec3& b) {
    segmentZeros(q, a, b, keep);
    const double va = planeValue(base, a), vb = planeValue(base, b);
    if ((va <= 0.0) != (vb <= 0.0) && va != vb) keep(a + (va / (va - vb)) * (b - a));
    if (va == 0.0) keep(a);
  });
  const FaceConic conic(q, cell.planes[size_t(f)], faceCentre(cell, f));
  for (int axis = 0; axis < 3; ++axis) conic.extremes(q, Vec3::Unit(axis), keep);
  return box;
}

std::pair<double, double> quadricRangeOnFace(const QuadricCoeffs& q, const ConvexCell& cell,
                                             int f) {
  double lo = kInfinity, hi = -kInfinity;
  const ConvexCell::Face& face = cell.faces[size_t(f)];
  if (face.empty()) return {lo, hi};
  const auto take = [&](const Vec3& p) {
    const double v = evalQuadric(q, p);
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  };
  for (int v : face) take(cell.vertices[size_t(v)]);
  // Along each edge, the parabola's vertex.
  faceEdges(cell, f, [&](const Vec3& a, const Vec3& b) {
    double qa, qb, qc;
    quadricAlongLine(q, a, b - a, qa, qb, qc);
    if (std::abs(qa) > 0.0) {
      const double s = -qb / (2.0 * qa);
      if (s > 0.0 && s < 1.0) take(a + s * (b - a));
    }
  });
  // The conic's centre (∇Q = 0 in the face), when inside the polygon.
  const Vec4& plane = cell.planes[size_t(f)];
  Vec3 u, w;
  planeBasis(plane, u, w);
  const Vec3 o = faceCentre(cell, f);
  const Mat3 M = quadraticPart(q);
  const Vec3 g = quadricGradient(q, o);
  const double A = u.dot(M * u), B = 2.0 * u.dot(M * w), C = w.dot(M * w);
  const double det = 4.0 * A * C - B * B;
  if (std::abs(det) > 1e-14 * (A * A + B * B + C * C) && det != 0.0) {
    // [2A B; B 2C] (s, r) = -(D, E)
    const double D = g.dot(u), E = g.dot(w);
    const double s = (-D * 2.0 * C + B * E) / det, r = (-2.0 * A * E + B * D) / det;
    const Vec3 p = o + s * u + r * w;
    if (cell.contains(p)) take(p);
  }
  return {lo, hi};
}

}  // namespace quadtri
