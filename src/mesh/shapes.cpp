#include "quadtri/mesh/shapes.h"

#include <fmt/ranges.h>

#include <array>
#include <charconv>
#include <cmath>
#include <map>

#include "quadtri/math/error.h"
#include "quadtri/mesh/isosurface.h"
#include "quadtri/mesh/normals.h"

namespace quadtri {
namespace {

// Distance from p to the ellipsoid x²/a²+y²/b²+z²/c²=1: the nearest point is
// q_i = a_i² p_i / (a_i² + s) for the root s of F(s) = Σ (a_i p_i / (a_i² + s))² - 1, the
// largest root (Eberly, "Distance from a point to an ellipse, an ellipsoid, or a
// hyperellipsoid"). F is monotone for s > -min a_i², so bisection is robust.
double ellipsoidDistance(const Vec3& radii, const Vec3& p) {
  const Vec3 q = p.cwiseAbs();
  auto F = [&](double s) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double r = radii[i] * q[i] / (radii[i] * radii[i] + s);
      sum += r * r;
    }
    return sum - 1.0;
  };
  const double minR2 = radii.cwiseAbs2().minCoeff();
  double lo = -minR2, hi = q.norm() * radii.maxCoeff();
  // F(lo+) may be finite when the component on the smallest axis vanishes; bisection on the
  // bracket [lo, hi] still converges to the relevant root of the monotone branch.
  // Until the bracket is two adjacent doubles (at most ~2100 halvings; some 60 in practice).
  for (int it = 0; it < 2200; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    if (F(mid) > 0.0)
      lo = mid;
    else
      hi = mid;
  }
  const double s = 0.5 * (lo + hi);
  Vec3 nearest;
  for (int i = 0; i < 3; ++i) nearest[i] = radii[i] * radii[i] * q[i] / (radii[i] * radii[i] + s);
  // Points deep inside, near the smallest axis, are handled by the same formula except when
  // that axis component is zero; project radially as a bound in that degenerate case.
  const double d = (nearest - q).norm();
  const Vec3 radial = q.cwiseQuotient(radii);
  const double rn = radial.norm();
  const double radialBound = rn > 0 ? (q - q / rn).norm() : radii.minCoeff();
  return std::min(d, radialBound);
}

// The genus-2 pretzel f = g² + z² − r², g = x⁴ − x² + y² (see AnalyticSurface).
ImplicitFunction genus2Function(double r) {
  ImplicitFunction f;
  f.value = [r](const Vec3& p) {
    const double x2 = p.x() * p.x();
    const double g = x2 * x2 - x2 + p.y() * p.y();
    return g * g + p.z() * p.z() - r * r;
  };
  f.gradient = [](const Vec3& p) {
    const double x2 = p.x() * p.x();
    const double g = x2 * x2 - x2 + p.y() * p.y();
    return Vec3(2 * g * (4 * x2 * p.x() - 2 * p.x()), 4 * g * p.y(), 2 * p.z());
  };
  return f;
}

// The pretzel's half length: its tips, where g = r on the x axis.
double genus2HalfLength(double r) {
  return std::sqrt((1 + std::sqrt(1 + 4 * r)) / 2);
}

constexpr double kGenus2Tube = 0.2;

TriangleMesh genus2Mesh(int cells) {
  const double r = kGenus2Tube;
  // |y| ≤ sqrt(1/4 + r) and |z| ≤ r on the surface; the uneven margins keep grid planes off
  // the symmetry planes, so the mesh is irregular and no grid point sits on the surface.
  const Vec3 half(genus2HalfLength(r) + 0.1031, std::sqrt(0.25 + r) + 0.1053, r + 0.1072);
  return marchingTetrahedra(genus2Function(r), -half, half + Vec3(0.0137, 0.0091, 0.0113), cells);
}

struct MeshBuilder {
  TriangleMesh mesh;
  uint32_t add(const Vec3& p) {
    mesh.positions.push_back(p);
    return uint32_t(mesh.positions.size() - 1);
  }
  void tri(uint32_t a, uint32_t b, uint32_t c) { mesh.triangles.push_back({a, b, c}); }
};

TriangleMesh icosahedron() {
  MeshBuilder m;
  const double phi = (1.0 + std::sqrt(5.0)) / 2.0;
  const double s = 1.0 / std::sqrt(1.0 + phi * phi);
  const double pts[12][3] = {{-1, phi, 0}, {1, phi, 0}, {-1, -phi, 0}, {1, -phi, 0},
                             {0, -1, phi}, {0, 1, phi}, {0, -1, -phi}, {0, 1, -phi},
                             {phi, 0, -1}, {phi, 0, 1}, {-phi, 0, -1}, {-phi, 0, 1}};
  for (auto& p : pts) m.add(Vec3(p[0], p[1], p[2]) * s);
  const uint32_t f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                             {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                             {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                             {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (auto& t : f) m.tri(t[0], t[1], t[2]);
  return m.mesh;
}

TriangleMesh subdivideOnSphere(const TriangleMesh& in) {
  TriangleMesh out;
  out.positions = in.positions;
  std::map<std::pair<uint32_t, uint32_t>, uint32_t> mid;
  auto midpoint = [&](uint32_t a, uint32_t b) {
    auto key = std::minmax(a, b);
    auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    out.positions.push_back((out.positions[a] + out.positions[b]).normalized());
    const uint32_t idx = uint32_t(out.positions.size() - 1);
    mid.emplace(key, idx);
    return idx;
  };
  for (const Tri& t : in.triangles) {
    const uint32_t ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.push_back({t[0], ab, ca});
    out.triangles.push_back({t[1], bc, ab});
    out.triangles.push_back({t[2], ca, bc});
    out.triangles.push_back({ab, bc, ca});
  }
  return out;
}

void setNormals(BuiltinMesh& b, bool analytic) {
  if (analytic && b.truth) {
    b.mesh.normals.clear();
    for (const Vec3& p : b.mesh.positions) b.mesh.normals.push_back(b.truth->normal(p));
    b.mesh.normalIndices = b.mesh.triangles;
  } else {
    computeVertexNormals(b.mesh, NormalSource::Average);
  }
}

// Grid over (major angle, profile angle) with wrap-around in both directions where `wrapRows`.
TriangleMesh torusMesh(double R, double r, int seg, int rings) {
  MeshBuilder m;
  for (int i = 0; i < seg; ++i)
    for (int j = 0; j < rings; ++j) {
      const double u = 2 * kPi * i / seg, v = 2 * kPi * j / rings;
      m.add(Vec3((R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u),
                 r * std::sin(v)));
    }
  auto id = [&](int i, int j) { return uint32_t((i % seg) * rings + (j % rings)); };
  for (int i = 0; i < seg; ++i)
    for (int j = 0; j < rings; ++j) {
      m.tri(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.tri(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m.mesh;
}

TriangleMesh uvSphereMesh(int seg, int rings) {
  MeshBuilder m;
  const uint32_t north = m.add(Vec3(0, 0, 1));
  for (int j = 1; j < rings; ++j)
    for (int i = 0; i < seg; ++i) {
      const double th = kPi * j / rings, ph = 2 * kPi * i / seg;
      m.add(Vec3(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph), std::cos(th)));
    }
  const uint32_t south = m.add(Vec3(0, 0, -1));
  auto id = [&](int j, int i) { return uint32_t(1 + (j - 1) * seg + (i % seg)); };
  for (int i = 0; i < seg; ++i) m.tri(north, id(1, i), id(1, i + 1));
  for (int j = 1; j < rings - 1; ++j)
    for (int i = 0; i < seg; ++i) {
      m.tri(id(j, i), id(j + 1, i), id(j + 1, i + 1));
      m.tri(id(j, i), id(j + 1, i + 1), id(j, i + 1));
    }
  for (int i = 0; i < seg; ++i) m.tri(south, id(rings - 1, i + 1), id(rings - 1, i));
  return m.mesh;
}

// The box [−1, 1]³: each face a grid of n×n squares, each cut along the same diagonal into two
// triangles, wound outwards. Grid coordinates are −1 + 2i/n on every face, so the faces' shared
// vertices weld by equality. Split normals: each face indexes its own normal.
TriangleMesh cubeMesh(int n) {
  TriangleMesh mesh;
  std::map<std::array<int, 3>, uint32_t> ids;
  auto coordinate = [n](int i) { return -1.0 + 2.0 * i / n; };
  auto vertex = [&](const std::array<int, 3>& g) {
    auto [it, inserted] = ids.try_emplace(g, uint32_t(mesh.positions.size()));
    if (inserted) mesh.positions.emplace_back(coordinate(g[0]), coordinate(g[1]), coordinate(g[2]));
    return it->second;
  };
  for (int axis = 0; axis < 3; ++axis)
    for (const int side : {-1, 1}) {
      // Tangent axes with u × v = side · e_axis.
      int u = (axis + 1) % 3, v = (axis + 2) % 3;
      if (side < 0) std::swap(u, v);
      Vec3 normal = Vec3::Zero();
      normal[axis] = side;
      const uint32_t ni = uint32_t(mesh.normals.size());
      mesh.normals.push_back(normal);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto at = [&](int di, int dj) {
            std::array<int, 3> g{};
            g[axis] = side < 0 ? 0 : n;
            g[u] = i + di;
            g[v] = j + dj;
            return vertex(g);
          };
          const uint32_t a = at(0, 0), b = at(1, 0), c = at(1, 1), d = at(0, 1);
          mesh.triangles.push_back({a, b, c});
          mesh.triangles.push_back({a, c, d});
          mesh.normalIndices.push_back({ni, ni, ni});
          mesh.normalIndices.push_back({ni, ni, ni});
        }
    }
  return mesh;
}

// The capped cylinder of radius 1 around the z axis, z from −1 to 1: `seg` vertices around,
// `rings` quads along the side (each cut into two triangles), each cap a fan of `seg` triangles
// around its centre. Split normals: the side's are radial, each cap has its own axial one.
TriangleMesh cylinderMesh(int seg, int rings) {
  TriangleMesh mesh;
  for (int j = 0; j <= rings; ++j)
    for (int i = 0; i < seg; ++i) {
      const double phi = 2 * kPi * i / seg;
      mesh.positions.emplace_back(std::cos(phi), std::sin(phi), -1.0 + 2.0 * j / rings);
    }
  for (int i = 0; i < seg; ++i)
    mesh.normals.push_back(Vec3(mesh.positions[i].x(), mesh.positions[i].y(), 0.0).normalized());
  auto id = [&](int j, int i) { return uint32_t(j * seg + (i % seg)); };
  for (int j = 0; j < rings; ++j)
    for (int i = 0; i < seg; ++i) {
      const uint32_t a = id(j, i), b = id(j, i + 1), c = id(j + 1, i + 1), d = id(j + 1, i);
      const uint32_t na = uint32_t(i), nb = uint32_t((i + 1) % seg);
      mesh.triangles.push_back({a, b, c});
      mesh.normalIndices.push_back({na, nb, nb});
      mesh.triangles.push_back({a, c, d});
      mesh.normalIndices.push_back({na, nb, na});
    }
  const uint32_t bottom = uint32_t(mesh.positions.size()), top = bottom + 1;
  mesh.positions.emplace_back(0.0, 0.0, -1.0);
  mesh.positions.emplace_back(0.0, 0.0, 1.0);
  const uint32_t nDown = uint32_t(mesh.normals.size()), nUp = nDown + 1;
  mesh.normals.emplace_back(0.0, 0.0, -1.0);
  mesh.normals.emplace_back(0.0, 0.0, 1.0);
  for (int i = 0; i < seg; ++i) {
    mesh.triangles.push_back({bottom, id(0, i + 1), id(0, i)});
    mesh.normalIndices.push_back({nDown, nDown, nDown});
    mesh.triangles.push_back({top, id(rings, i), id(rings, i + 1)});
    mesh.normalIndices.push_back({nUp, nUp, nUp});
  }
  return mesh;
}

std::vector<double> parseNumbers(std::string_view spec, std::string_view args) {
  std::vector<double> out;
  while (!args.empty()) {
    const size_t comma = args.find(',');
    const std::string token(args.substr(0, comma));
    try {
      size_t used = 0;
      out.push_back(std::stod(token, &used));
      if (used != token.size()) throw std::invalid_argument(token);
    } catch (const std::exception&) {
      fail("built-in shape '{}': '{}' is not a number", spec, token);
    }
    if (comma == std::string_view::npos) break;
    args.remove_prefix(comma + 1);
  }
  return out;
}

}  // namespace

double AnalyticSurface::distance(const Vec3& p) const {
  switch (kind) {
    case Kind::Sphere:
      return std::abs(p.norm() - a);
    case Kind::Ellipsoid:
      return ellipsoidDistance(Vec3(a, b, c), p);
    case Kind::Torus: {
      const double rho = std::hypot(p.x(), p.y()) - a;
      return std::abs(std::hypot(rho, p.z()) - b);
    }
    case Kind::Genus2: {
      const ImplicitFunction f = genus2Function(a);
      // The critical points of f lie on z = 0, where ∂f/∂z = 2z vanishes: a nudge along z
      // gives Newton a direction there.
      for (const double nudge : {0.0, 1e-3}) {
        try {
          // Newton lands near, not at, the nearest point (its path follows ∇f, which bends);
          // projecting p onto the tangent plane there and landing again converges to the foot
          // point at a rate of about dκ per round. Every q is on the surface: an upper bound.
          Vec3 q = projectOntoZeroSet(f, p + Vec3(0, 0, nudge * size()));
          double best = (q - p).norm();
          for (int round = 0; round < 8; ++round) {
            const Vec3 n = f.gradient(q).normalized();
            const Vec3 next = projectOntoZeroSet(f, p - (p - q).dot(n) * n);
            const double moved = (next - q).norm();
            q = next;
            best = std::min(best, (q - p).norm());
            if (moved <= 1e-15 * size()) break;
          }
          return best;
        } catch (const Error&) {
        }
      }
      const double g = f.gradient(p).norm();
      return g > 0 ? std::abs(f.value(p)) / g : size();
    }
    case Kind::Box: {
      const Vec3 q = p.cwiseAbs() - Vec3(a, b, c);
      if (q.maxCoeff() <= 0.0) return -q.maxCoeff();
      return q.cwiseMax(0.0).norm();
    }
    case Kind::Cylinder: {
      const double dr = std::hypot(p.x(), p.y()) - a, dz = std::abs(p.z()) - b;
      if (dr <= 0.0 && dz <= 0.0) return std::min(-dr, -dz);
      return std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
    }
  }
  return 0.0;
}

Vec3 AnalyticSurface::normal(const Vec3& p) const {
  switch (kind) {
    case Kind::Sphere:
      return safeNormalized(p);
    case Kind::Ellipsoid:
      return safeNormalized(Vec3(p.x() / (a * a), p.y() / (b * b), p.z() / (c * c)));
    case Kind::Torus: {
      const double rxy = std::hypot(p.x(), p.y());
      const Vec3 center = rxy > 0 ? Vec3(p.x() / rxy * a, p.y() / rxy * a, 0.0) : Vec3(a, 0, 0);
      return safeNormalized(p - center);
    }
    case Kind::Genus2: {
      const ImplicitFunction f = genus2Function(a);
      try {
        return safeNormalized(f.gradient(projectOntoZeroSet(f, p)));
      } catch (const Error&) {
        return safeNormalized(f.gradient(p));
      }
    }
    case Kind::Box: {
      const Vec3 q = p.cwiseAbs() - Vec3(a, b, c);
      const Vec3 sign(p.x() < 0 ? -1.0 : 1.0, p.y() < 0 ? -1.0 : 1.0, p.z() < 0 ? -1.0 : 1.0);
      if (q.maxCoeff() > 0.0) return safeNormalized(q.cwiseMax(0.0).cwiseProduct(sign));
      int axis = 0;
      q.maxCoeff(&axis);
      Vec3 n = Vec3::Zero();
      n[axis] = sign[axis];
      return n;
    }
    case Kind::Cylinder: {
      const double rxy = std::hypot(p.x(), p.y());
      const double dr = rxy - a, dz = std::abs(p.z()) - b;
      const Vec3 radial = rxy > 0 ? Vec3(p.x() / rxy, p.y() / rxy, 0.0) : Vec3(1, 0, 0);
      const Vec3 axial(0.0, 0.0, p.z() < 0 ? -1.0 : 1.0);
      if (dr > 0.0 && dz > 0.0) return safeNormalized(dr * radial + dz * axial);
      return dr >= dz ? radial : axial;
    }
  }
  return Vec3(0, 0, 1);
}

double AnalyticSurface::size() const {
  switch (kind) {
    case Kind::Sphere:
      return a;
    case Kind::Ellipsoid:
      return std::max({a, b, c});
    case Kind::Torus:
      return a + b;
    case Kind::Genus2:
      return genus2HalfLength(a);
    case Kind::Box:
      return std::max({a, b, c});
    case Kind::Cylinder:
      return std::max(a, b);
  }
  return 1.0;
}

const std::vector<std::string>& builtinShapeNames() {
  static const std::vector<std::string> names = {
      "triangle",  "tetrahedron", "icosahedron", "icosphere", "uv-sphere",
      "ellipsoid", "torus",       "genus2",      "cube",      "cylinder"};
  return names;
}

namespace {

/// Segments × rings of a uv-sphere, torus or cylinder: at most kMaxGridCells (2·that many
/// triangles, about an icosphere of level 8), so that no spec builds more than memory holds.
constexpr int64_t kMaxGridCells = int64_t(1) << 20;

void checkGridSize(std::string_view shape, int segments, int rings) {
  if (int64_t(segments) * int64_t(rings) > kMaxGridCells)
    fail("{} of {} segments and {} rings is too fine: segments x rings must be at most {}", shape,
         segments, rings, kMaxGridCells);
}

/// Lengths (radii) must be finite and within 1e-6 to 1e6, the scales quadtri is tested at.
void checkLength(std::string_view what, double x) {
  if (!(x >= 1e-6 && x <= 1e6)) fail("{} {} is out of range: expected 1e-6 to 1e6", what, x);
}

}  // namespace

BuiltinMesh makeBuiltin(std::string_view name, const ShapeParams& params) {
  BuiltinMesh b;
  const AnalyticSurface unitSphere{AnalyticSurface::Kind::Sphere, 1, 1, 1};
  if (name == "triangle") {
    // An equilateral triangle cut from the unit sphere 50° around the pole, carrying the sphere's
    // normals: the thesis' single curved triangle.
    const double th = 50.0 * kPi / 180.0;
    for (int i = 0; i < 3; ++i) {
      const double ph = 2 * kPi * i / 3 + kPi / 2;
      b.mesh.positions.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                                    std::cos(th));
    }
    b.mesh.triangles.push_back({0, 1, 2});
    b.truth = unitSphere;
    b.description = "spherical triangle";
    setNormals(b, true);  // averaging one face would give a flat normal: the sphere's is the point
    return b;
  }
  if (name == "tetrahedron") {
    const double s = 1.0 / std::sqrt(3.0);
    b.mesh.positions = {Vec3(1, 1, 1) * s, Vec3(1, -1, -1) * s, Vec3(-1, 1, -1) * s,
                        Vec3(-1, -1, 1) * s};
    b.mesh.triangles = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
    b.truth = unitSphere;
    b.description = "regular tetrahedron";
  } else if (name == "icosahedron" || name == "icosphere") {
    b.mesh = icosahedron();
    const int level = name == "icosahedron" ? 0 : params.level;
    if (level < 0 || level > 8) fail("icosphere level {} is out of range: expected 0 to 8", level);
    for (int i = 0; i < level; ++i) b.mesh = subdivideOnSphere(b.mesh);
    b.truth = unitSphere;
    b.description = level == 0 ? "icosahedron" : fmt::format("icosphere level {}", level);
  } else if (name == "uv-sphere") {
    if (params.segments < 3 || params.rings < 2)
      fail("uv-sphere needs at least 3 segments and 2 rings");
    checkGridSize("uv-sphere", params.segments, params.rings);
    b.mesh = uvSphereMesh(params.segments, params.rings);
    b.truth = unitSphere;
    b.description = fmt::format("uv-sphere {}x{}", params.segments, params.rings);
  } else if (name == "ellipsoid") {
    const Vec3& r = params.radii;
    if (!(r.minCoeff() > 0)) fail("ellipsoid radii must be positive");
    checkLength("ellipsoid radius", r.minCoeff());
    checkLength("ellipsoid radius", r.maxCoeff());
    if (params.level < 0 || params.level > 8)
      fail("ellipsoid level {} is out of range: expected 0 to 8", params.level);
    b.mesh = icosahedron();
    for (int i = 0; i < params.level; ++i) b.mesh = subdivideOnSphere(b.mesh);
    for (Vec3& p : b.mesh.positions) p = p.cwiseProduct(r);
    b.truth = AnalyticSurface{AnalyticSurface::Kind::Ellipsoid, r.x(), r.y(), r.z()};
    b.description = fmt::format("ellipsoid {}x{}x{} level {}", r.x(), r.y(), r.z(), params.level);
  } else if (name == "torus") {
    if (!(params.major > params.minor && params.minor > 0)) fail("torus needs major > minor > 0");
    if (params.segments < 3 || params.rings < 3)
      fail("torus needs at least 3 segments and 3 rings");
    checkLength("torus major radius", params.major);
    checkLength("torus minor radius", params.minor);
    checkGridSize("torus", params.segments, params.rings);
    b.mesh = torusMesh(params.major, params.minor, params.segments, params.rings);
    b.truth = AnalyticSurface{AnalyticSurface::Kind::Torus, params.major, params.minor, 0};
    b.description = fmt::format("torus R={} r={} {}x{}", params.major, params.minor,
                                params.segments, params.rings);
  } else if (name == "genus2") {
    if (params.cells < 8 || params.cells > 1024)
      fail("genus2 cells {} is out of range: expected 8 to 1024", params.cells);
    b.mesh = genus2Mesh(params.cells);
    b.truth = AnalyticSurface{AnalyticSurface::Kind::Genus2, kGenus2Tube, 0, 0};
    b.description = fmt::format("genus-2 pretzel, {} cells", params.cells);
  } else if (name == "cube" || name == "cylinder") {
    const bool cube = name == "cube";
    if (cube && (params.divisions < 1 || params.divisions > 1024))
      fail("cube divisions {} is out of range: expected 1 to 1024", params.divisions);
    if (!cube && (params.segments < 3 || params.rings < 1))
      fail("cylinder needs at least 3 segments and 1 ring");
    if (!cube) checkGridSize("cylinder", params.segments, params.rings);
    b.mesh = cube ? cubeMesh(params.divisions) : cylinderMesh(params.segments, params.rings);
    b.truth = AnalyticSurface{cube ? AnalyticSurface::Kind::Box : AnalyticSurface::Kind::Cylinder,
                              1, 1, 1};
    b.description = cube ? fmt::format("cube, {} divisions", params.divisions)
                         : fmt::format("capped cylinder {}x{}", params.segments, params.rings);
    // The analytic normals are the split ones built with the mesh (AnalyticSurface::normal
    // cannot tell which face a crease vertex belongs to).
    if (!params.analyticNormals) computeVertexNormals(b.mesh, NormalSource::Average);
    return b;
  } else {
    fail("unknown built-in shape '{}': expected one of {}", name,
         fmt::join(builtinShapeNames(), ", "));
  }
  setNormals(b, params.analyticNormals);
  return b;
}

std::optional<ShapeSpec> parseShapeSpec(std::string_view spec) {
  const size_t colon = spec.find(':');
  const std::string_view name = spec.substr(0, colon);
  const auto& names = builtinShapeNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) return std::nullopt;
  const std::vector<double> v = colon == std::string_view::npos
                                    ? std::vector<double>{}
                                    : parseNumbers(spec, spec.substr(colon + 1));
  ShapeParams p;
  // A count must be a whole number that fits an int (a cast of 1e300 or NaN is undefined);
  // makeBuiltin checks its range.
  auto count = [&](size_t i) {
    if (!(v[i] == std::floor(v[i]) && std::abs(v[i]) <= 1e9))
      fail("built-in shape '{}': number {} ({}) must be a whole number", spec, i + 1, v[i]);
    return int(v[i]);
  };
  auto need = [&](size_t lo, size_t hi) {
    if (v.size() < lo || v.size() > hi)
      fail("built-in shape '{}': expected {} to {} numbers after ':'", spec, lo, hi);
  };
  if (name == "icosphere") {
    need(0, 1);
    if (!v.empty()) p.level = count(0);
  } else if (name == "uv-sphere") {
    need(0, 2);
    if (v.size() > 0) p.segments = count(0);
    if (v.size() > 1) p.rings = count(1);
  } else if (name == "ellipsoid") {
    need(0, 4);
    if (v.size() >= 3)
      p.radii = Vec3(v[0], v[1], v[2]);
    else if (!v.empty())
      fail("built-in shape '{}': an ellipsoid takes three radii (and a level)", spec);
    if (v.size() == 4) p.level = count(3);
  } else if (name == "torus") {
    need(0, 4);
    if (v.size() >= 2) {
      p.major = v[0];
      p.minor = v[1];
    } else if (!v.empty())
      fail("built-in shape '{}': a torus takes R,r (and segments,rings)", spec);
    if (v.size() >= 3) p.segments = count(2);
    if (v.size() >= 4) p.rings = count(3);
  } else if (name == "genus2") {
    need(0, 1);
    if (!v.empty()) p.cells = count(0);
  } else if (name == "cube") {
    need(0, 1);
    if (!v.empty()) p.divisions = count(0);
  } else if (name == "cylinder") {
    need(0, 2);
    if (v.size() > 0) p.segments = count(0);
    if (v.size() > 1) p.rings = count(1);
  } else {
    need(0, 0);
  }
  return ShapeSpec{std::string(name), p};
}

std::optional<BuiltinMesh> parseBuiltinSpec(std::string_view spec) {
  const std::optional<ShapeSpec> shape = parseShapeSpec(spec);
  if (!shape) return std::nullopt;
  return makeBuiltin(shape->name, shape->params);
}

uint64_t builtinTriangleCount(const ShapeSpec& shape) {
  const ShapeParams& p = shape.params;
  const std::string& name = shape.name;
  const auto grid = [](int a, int b) -> uint64_t {
    return a > 0 && b > 0 ? 2 * uint64_t(a) * uint64_t(b) : 0;
  };
  if (name == "triangle") return 1;
  if (name == "tetrahedron") return 4;
  if (name == "icosahedron") return 20;
  if (name == "icosphere" || name == "ellipsoid")
    return p.level >= 0 && p.level <= 8 ? uint64_t(20) << (2 * p.level) : 0;
  if (name == "uv-sphere" || name == "torus") return grid(p.segments, p.rings);
  if (name == "cylinder") return grid(p.segments, p.rings + 1);  // the side and two fans
  if (name == "cube") return 6 * grid(p.divisions, p.divisions);
  if (name == "genus2") return p.cells > 0 ? 16 * uint64_t(p.cells) * uint64_t(p.cells) : 0;
  return 0;
}

}  // namespace quadtri
