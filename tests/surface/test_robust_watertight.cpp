// The robust implicit model's cells (exact bounds and checks) and its watertightness on the
// configurations that cracked the bridge-only design: each fixture below is a small mesh
// built here, with the crack counts it had before the cells (commit f206f19) in its comment.
#include <gtest/gtest.h>

#include <map>
#include <random>

#include "quadtri/analysis/crack_rate.h"
#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/math/error.h"
#include "quadtri/mesh/normals.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/mesh/topology.h"
#include "quadtri/surface/robust_cell.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

Vec4 plane(const Vec3& n, double d) {
  return Vec4(n.x(), n.y(), n.z(), d);
}

// A box cell lo <= x <= hi.
ConvexCell boxCell(const Vec3& lo, const Vec3& hi) {
  std::vector<Vec4> planes;
  for (int axis = 0; axis < 3; ++axis) {
    planes.push_back(plane(Vec3::Unit(axis), -lo[axis]));
    planes.push_back(plane(-Vec3::Unit(axis), hi[axis]));
  }
  return makeConvexCell(planes, 1e-12);
}

TEST(ConvexCell, TriangularPrismHasItsSixVerticesAndFiveFaces) {
  const std::vector<Vec4> planes = {plane(Vec3(1, 0, 0), 0), plane(Vec3(0, 1, 0), 0),
                                    plane(Vec3(-1, -1, 0).normalized(), std::sqrt(0.5)),
                                    plane(Vec3(0, 0, 1), 1), plane(Vec3(0, 0, -1), 2)};
  const ConvexCell cell = makeConvexCell(planes, 1e-12);
  ASSERT_EQ(cell.vertices.size(), 6u);
  const std::vector<size_t> faceSizes = {4, 4, 4, 3, 3};
  for (size_t f = 0; f < 5; ++f) EXPECT_EQ(cell.faces[f].size(), faceSizes[f]) << f;
  const Bounds3 b = cell.bounds();
  EXPECT_LT((b.lo - Vec3(0, 0, -1)).norm(), 1e-15);
  EXPECT_LT((b.hi - Vec3(1, 1, 2)).norm(), 1e-15);
  // A sixth plane that misses the prism leaves it unchanged; one that cuts a corner adds one.
  std::vector<Vec4> more = planes;
  more.push_back(plane(Vec3(0, 0, -1), 5));
  EXPECT_EQ(makeConvexCell(more, 1e-12).vertices.size(), 6u);
  more.back() = plane(Vec3(-1, 0, 0), 0.5);  // x <= 0.5
  EXPECT_EQ(makeConvexCell(more, 1e-12).vertices.size(), 8u);
}

TEST(ConvexCell, SevenPlanesMakeTheirPolytopeAndAnEighthIsRefused) {
  // A unit cube with one corner cut off (x + y + z <= 2.5): 7 planes, the most a cell holds
  // (a patch's six clip planes and the fold check's plane), 10 vertices, 2·7 − 4.
  std::vector<Vec4> planes;
  for (int axis = 0; axis < 3; ++axis) {
    planes.push_back(plane(Vec3::Unit(axis), 0));
    planes.push_back(plane(-Vec3::Unit(axis), 1));
  }
  planes.push_back(plane(-Vec3(1, 1, 1).normalized(), 2.5 / std::sqrt(3.0)));
  const ConvexCell cell = makeConvexCell(planes, 1e-12);
  EXPECT_EQ(cell.vertices.size(), 10u);
  ASSERT_EQ(cell.faces.size(), 7u);
  const std::vector<size_t> faceSizes = {4, 5, 4, 5, 4, 5, 3};
  for (size_t f = 0; f < 7; ++f) EXPECT_EQ(cell.faces[f].size(), faceSizes[f]) << f;
  EXPECT_TRUE(cell.contains(Vec3(0.5, 0.5, 0.5)));
  EXPECT_FALSE(cell.contains(Vec3(0.9, 0.9, 0.9)));
  // Four planes through one point (a pyramid's apex) merge into one vertex.
  const std::vector<Vec4> pyramid = {
      plane(Vec3(1, 0, 1).normalized(), 0), plane(Vec3(-1, 0, 1).normalized(), 0),
      plane(Vec3(0, 1, 1).normalized(), 0), plane(Vec3(0, -1, 1).normalized(), 0),
      plane(Vec3(0, 0, -1), 1)};
  const ConvexCell apex = makeConvexCell(pyramid, 1e-12);
  EXPECT_EQ(apex.vertices.size(), 5u);
  planes.push_back(plane(Vec3(0, 0, 1), 0));
  EXPECT_THROW(makeConvexCell(planes, 1e-12), Error);
}

TEST(ConvexCell, MoreTriplePointsThanItHoldsMarkItOverflowed) {
  // Seven nearly vertical planes through nearly one point, offsets of the order of the
  // tolerance (found by a random search): their triple points spread along the axis, far
  // further apart than the merge radius, and more than 12 of them lie within the tolerance of
  // every plane. The cell cannot hold them and says so; with a tight tolerance it can.
  const std::vector<Vec4> planes = {
      {-0.98376929605414731, 0.17915909728542326, 0.0099995000374968768, 0.00039332986666017655},
      {-0.58745785564181741, -0.80919297935889056, 0.0099995000374968768, 0.00015944279705616094},
      {-0.036886171130044845, -0.99926944333266066, 0.0099995000374968768, -0.00064550774525900145},
      {0.85566320288106157, -0.51743646299263024, 0.0099995000374968768, 0.00021740516812841237},
      {0.96475980749464818, 0.26294205415241123, 0.0099995000374968768, -0.00075690306188309052},
      {-0.036398371117109335, 0.999287330340489, 0.0099995000374968768, -0.0003780401590808641},
      {-0.61133761475338155, 0.79130672358235798, 0.0099995000374968768, -0.00087557689135370545}};
  const ConvexCell loose = makeConvexCell(planes, 1e-3);
  EXPECT_TRUE(loose.overflowed);
  EXPECT_EQ(loose.vertices.size(), ConvexCell::kMaxVertices);
  const ConvexCell tight = makeConvexCell(planes, 1e-12);
  EXPECT_FALSE(tight.overflowed);
  EXPECT_LE(tight.vertices.size(), 2 * planes.size() - 4);
}

TEST(ConvexCell, OverlapNeedsMoreThanTouching) {
  const ConvexCell a = boxCell(Vec3(0, 0, 0), Vec3(1, 1, 1));
  EXPECT_TRUE(cellsOverlap(a, boxCell(Vec3(0.5, 0.5, 0.5), Vec3(2, 2, 2)), 1e-12));
  EXPECT_FALSE(cellsOverlap(a, boxCell(Vec3(1, 0, 0), Vec3(2, 1, 1)), 1e-12));  // a shared face
  EXPECT_FALSE(cellsOverlap(a, boxCell(Vec3(1.5, 0, 0), Vec3(2, 1, 1)), 1e-12));
  // Boxes whose projections on all face normals overlap, separated by an edge-edge axis: the
  // unit cube and a thin slab x + y >= 2.1 (a tetrahedron-like sliver beyond the edge x=y=1).
  const std::vector<Vec4> planes = {plane(Vec3(1, 1, 0).normalized(), -2.1 / std::sqrt(2.0)),
                                    plane(Vec3(-1, 0, 0), 2), plane(Vec3(0, -1, 0), 2),
                                    plane(Vec3(0, 0, 1), 0), plane(Vec3(0, 0, -1), 1)};
  EXPECT_FALSE(cellsOverlap(a, makeConvexCell(planes, 1e-12), 1e-12));
}

TEST(ConvexCell, QuadricBoundsAreTheExactBoxOfTheClippedSurface) {
  // The cap z >= 1/2 of the unit sphere: |x|, |y| <= √(3/4) on its rim, z in [1/2, 1].
  const QuadricCoeffs sphere = {1, 1, 1, 0, 0, 0, 0, 0, 0, -1};
  Bounds3 b = quadricBoundsInCell(sphere, boxCell(Vec3(-2, -2, 0.5), Vec3(2, 2, 2)));
  const double r = std::sqrt(0.75);
  EXPECT_NEAR(b.lo.x(), -r, 1e-15);
  EXPECT_NEAR(b.hi.y(), r, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.5, 1e-15);
  EXPECT_NEAR(b.hi.z(), 1.0, 1e-15);
  // x²/4 + y² + 4z² = 1 for z >= 1/4: the rim x = ±2√(3/4), y = ±√(3/4); the top z = 1/2.
  const QuadricCoeffs ellipsoid = {0.25, 1, 4, 0, 0, 0, 0, 0, 0, -1};
  b = quadricBoundsInCell(ellipsoid, boxCell(Vec3(-3, -3, 0.25), Vec3(3, 3, 3)));
  EXPECT_NEAR(b.hi.x(), 2 * r, 1e-15);
  EXPECT_NEAR(b.lo.y(), -r, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.25, 1e-15);
  EXPECT_NEAR(b.hi.z(), 0.5, 1e-15);
  // Clipped by the cell's sides too: |x| <= 1 cuts the rim; the extreme in y is then inside.
  b = quadricBoundsInCell(ellipsoid, boxCell(Vec3(-1, -3, 0.25), Vec3(1, 3, 3)));
  EXPECT_NEAR(b.hi.x(), 1.0, 1e-15);
  EXPECT_NEAR(b.hi.y(), r, 1e-15);
  // A cell the surface misses.
  EXPECT_TRUE(quadricBoundsInCell(sphere, boxCell(Vec3(2, 2, 2), Vec3(3, 3, 3))).empty());
}

TEST(ConvexCell, BetweenBoundsOnAFaceAreTheExactBoxOfTheRegion) {
  // Face y = 0 of [-1,1]×[0,1]×[-1,1]; the circle x² + (z+1)² = 9/4 on it and the base z = 0:
  // where the sphere says inside and the base outside, |x| <= 1 (the face's sides) and
  // 0 <= z <= 1/2 (the circle's top).
  const ConvexCell cell = boxCell(Vec3(-1, 0, -1), Vec3(1, 1, 1));
  const QuadricCoeffs sphere = {1, 1, 1, 0, 0, 0, 0, 0, 2, 1 - 2.25};
  const int face = 2;  // y >= 0
  ASSERT_EQ(cell.planes[face], plane(Vec3(0, 1, 0), 0));
  const Bounds3 b = betweenBoundsOnFace(sphere, 1.0, plane(Vec3(0, 0, 1), 0), cell, face);
  EXPECT_NEAR(b.lo.x(), -1.0, 1e-15);
  EXPECT_NEAR(b.hi.x(), 1.0, 1e-15);
  EXPECT_NEAR(b.lo.z(), 0.0, 1e-15);
  EXPECT_NEAR(b.hi.z(), 0.5, 1e-15);
  EXPECT_EQ(b.lo.y(), 0.0);
  EXPECT_EQ(b.hi.y(), 0.0);
  // A base above the whole face: the region is the face's part of the disc, down to the
  // face's lower side z = -1.
  const Bounds3 c = betweenBoundsOnFace(sphere, 1.0, plane(Vec3(0, 0, -1), 5), cell, face);
  EXPECT_NEAR(c.lo.z(), -1.0, 1e-15);
  EXPECT_NEAR(c.hi.z(), 0.5, 1e-15);
  EXPECT_NEAR(c.lo.x(), -1.0, 1e-15);
  // The sphere's inside with the base's below everywhere: nothing between them.
  EXPECT_TRUE(betweenBoundsOnFace(QuadricCoeffs{0, 0, 0, 0, 0, 0, 0, 0, 0, -1}, 1.0,
                                  plane(Vec3(0, 0, -1), -5), cell, face)
                  .empty());
}

// Cracked lines of the robust model of `mesh` among `count` crack-rate lines.
size_t crackedLines(const std::shared_ptr<const TriangleMesh>& mesh, size_t count,
                    uint64_t seed = 1) {
  const RobustImplicitModel model(mesh);
  CrackRateOptions options;
  options.lines = count;
  options.seed = seed;
  return size_t(
      std::llround(crackRate(modelGeometry(model, Tessellation{}), options) * double(count)));
}

std::shared_ptr<TriangleMesh> withAveragedNormals(std::vector<Vec3> positions,
                                                  std::vector<Tri> triangles) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = std::move(positions);
  mesh->triangles = std::move(triangles);
  computeVertexNormals(*mesh, NormalSource::Average);
  return mesh;
}

// An L-shaped block: the profile of three unit squares (an L of arms 2) extruded 0.5 along y,
// each square and side a pair of triangles; averaged normals. At its sharp and re-entrant
// edges neighbouring fits bend away from each other, and the lens between their conics
// reached past the thinner side's slab, where the bridge-only design's bridges (clipped to
// both slabs and the edge's ends) did not cover it (723 of 100,000 lines cracked before).
std::shared_ptr<TriangleMesh> lBlock() {
  std::vector<Vec3> v;
  std::map<std::array<int, 3>, uint32_t> index;
  const auto id = [&](int i, int k, int j) {
    const auto [it, inserted] = index.try_emplace({i, k, j}, uint32_t(v.size()));
    if (inserted) v.emplace_back(i, 0.5 * j, k);
    return it->second;
  };
  std::vector<Tri> t;
  const auto quad = [&](uint32_t a, uint32_t b, uint32_t c, uint32_t d) {
    t.push_back(Tri{a, b, c});
    t.push_back(Tri{a, c, d});
  };
  for (const auto& [i, k] : std::vector<std::pair<int, int>>{{0, 0}, {1, 0}, {0, 1}}) {
    quad(id(i, k, 0), id(i + 1, k, 0), id(i + 1, k + 1, 0), id(i, k + 1, 0));
    quad(id(i, k, 1), id(i, k + 1, 1), id(i + 1, k + 1, 1), id(i + 1, k, 1));
  }
  const int loop[8][2] = {{0, 0}, {1, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}, {0, 1}};
  for (int n = 0; n < 8; ++n) {
    const int* p = loop[n];
    const int* q = loop[(n + 1) % 8];
    quad(id(p[0], p[1], 0), id(p[0], p[1], 1), id(q[0], q[1], 1), id(q[0], q[1], 0));
  }
  return withAveragedNormals(v, t);
}

// A square pyramid, averaged normals: ~60° from the faces at the base, so every fit bends hard.
// The bridge-only design kept the sheet facing the face normal and classified inside and
// outside by it, which jumped where no sheet was (1,015 of its 1,377 cracked lines of 100,000),
// and clipped sheets that left their slab or sampled box (251 and 65).
std::shared_ptr<TriangleMesh> pyramid() {
  const double s = 0.55;
  return withAveragedNormals(
      {Vec3(-1, -s, -s), Vec3(-1, -s, s), Vec3(-1, s, s), Vec3(-1, s, -s), Vec3(1, 0.05, 0)},
      {Tri{1, 0, 4}, Tri{2, 1, 4}, Tri{3, 2, 4}, Tri{0, 3, 4}, Tri{0, 1, 2}, Tri{0, 2, 3}});
}

// A plate 2 × 2 × 0.02 of 12 triangles, averaged normals. The bridge-only design dropped the
// parts of its thin sheets that faced away from their face (7,680 of its 10,288 cracked lines
// of 100,000).
// A plate [-1,1]² × [-h,h] of 12 triangles (two per face); `normal(p, n)` gives the shading
// normal at corner p of a face with outward normal n (per corner, so faces need not agree).
template <typename Normal>
std::shared_ptr<TriangleMesh> plate(double h, const Normal& normal) {
  auto mesh = std::make_shared<TriangleMesh>();
  for (double z : {-h, h})
    for (double y : {-1.0, 1.0})
      for (double x : {-1.0, 1.0}) mesh->positions.emplace_back(x, y, z);
  const auto id = [](int x, int y, int z) { return uint32_t(4 * z + 2 * y + x); };
  const std::vector<std::array<uint32_t, 4>> quads = {
      {id(0, 0, 0), id(0, 1, 0), id(1, 1, 0), id(1, 0, 0)},
      {id(0, 0, 1), id(1, 0, 1), id(1, 1, 1), id(0, 1, 1)},
      {id(0, 0, 0), id(0, 0, 1), id(0, 1, 1), id(0, 1, 0)},
      {id(1, 0, 0), id(1, 1, 0), id(1, 1, 1), id(1, 0, 1)},
      {id(0, 0, 0), id(1, 0, 0), id(1, 0, 1), id(0, 0, 1)},
      {id(0, 1, 0), id(0, 1, 1), id(1, 1, 1), id(1, 1, 0)}};
  for (const auto& q : quads)
    for (const Tri& t : {Tri{q[0], q[1], q[2]}, Tri{q[0], q[2], q[3]}}) {
      mesh->triangles.push_back(t);
      const Vec3 n = mesh->faceNormal(mesh->triangles.size() - 1);
      Tri normals;
      for (int k = 0; k < 3; ++k) {
        mesh->normals.push_back(normal(mesh->positions[t[k]], n).normalized());
        normals[k] = uint32_t(mesh->normals.size() - 1);
      }
      mesh->normalIndices.push_back(normals);
    }
  return mesh;
}

// A plate 2 × 2 × 0.02, averaged normals.
std::shared_ptr<TriangleMesh> thinPlate() {
  auto mesh = plate(0.01, [](const Vec3&, const Vec3& n) { return n; });
  computeVertexNormals(*mesh, NormalSource::Average);
  return mesh;
}

// An octahedron with the sphere's normals, except triangle 0 whose corner normals point into
// the solid (reversed and tilted at random by up to ~20°). The bridge-only design let these
// normals turn the patch inside out; it fell back to its plane, which met neither its
// neighbours' bridges nor their inside (14,108 of 100,000 lines cracked before).
std::shared_ptr<TriangleMesh> octahedronWithAReversedFace() {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                     Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
  for (uint32_t a : {0u, 1u})
    for (uint32_t b : {2u, 3u})
      for (uint32_t c : {4u, 5u}) {
        Tri t{a, b, c};
        const Vec3 centre = (mesh->positions[a] + mesh->positions[b] + mesh->positions[c]) / 3.0;
        mesh->triangles.push_back(t);
        if (mesh->faceCross(mesh->triangles.size() - 1).dot(centre) < 0.0)
          mesh->triangles.back() = Tri{a, c, b};
      }
  mesh->normals = mesh->positions;
  mesh->normalIndices = mesh->triangles;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> jitter(-0.2, 0.2);
  for (int k = 0; k < 3; ++k) {
    const Vec3 n = -mesh->positions[mesh->triangles[0][k]];
    mesh->normals.push_back((n + Vec3(jitter(rng), jitter(rng), jitter(rng))).normalized());
    mesh->normalIndices[0][k] = uint32_t(mesh->normals.size() - 1);
  }
  return mesh;
}

TEST(RobustWatertight, LBlockWithAveragedNormals) {
  const auto mesh = lBlock();
  ASSERT_EQ(mesh->triangleCount(), 28u);
  ASSERT_TRUE(MeshTopology(*mesh).isClosed());
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustWatertight, PyramidWithAveragedNormals) {
  const auto mesh = pyramid();
  ASSERT_TRUE(MeshTopology(*mesh).isClosed());
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustWatertight, ThinPlateWithAveragedNormals) {
  const auto mesh = thinPlate();
  ASSERT_TRUE(MeshTopology(*mesh).isClosed());
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustWatertight, RazorThinPlateWithAFaceWhoseNormalsPointInside) {
  // 1e-7 thick, so a line through it crosses both large faces within crackRate's merge
  // distance (1e-7 of the diagonal), where only the directions keep the two crossings apart.
  // The upper face's normals point down: when its patch faced where they point, both
  // crossings read as entering and merged into one (49,315 of 100,000 lines cracked).
  const auto mesh = plate(
      5e-8, [](const Vec3& p, const Vec3& n) { return n.z() > 0.5 ? Vec3(-Vec3::UnitZ()) : n; });
  ASSERT_TRUE(MeshTopology(*mesh).isClosed());
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

// Lines as crackRate draws them whose crossings with the model, once crossings closer than
// crackRate's merge distance that cross the same way are taken as one, do not alternate
// between entering and leaving: where the model's surface crosses itself (one sheet reaching
// through another).
size_t linesNotAlternating(const RobustImplicitModel& model, size_t count) {
  Accel accel(Accel::Options{true, true});
  addModelGeometry(accel, model, Tessellation{});
  accel.commit();
  Bounds3 box = accel.bounds();
  const double diagonal = box.diagonal().norm();
  box.inflate(0.05 * diagonal);
  const double merge = 1e-7 * diagonal;
  size_t bad = 0;
  std::vector<RayHit> hits;
  for (size_t i = 0; i < count; ++i) {
    Pcg32 rng(17, i);
    const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
    const Vec3 o = box.lo + box.diagonal().cwiseProduct(u);
    const double z = 1.0 - 2.0 * rng.nextDouble(), phi = 2.0 * kPi * rng.nextDouble();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    std::vector<std::pair<double, bool>> line;
    for (double sign : {1.0, -1.0}) {
      hits.clear();
      accel.allHits(Ray{o, sign * d, 0.0, 2.0 * diagonal}, hits);
      for (const RayHit& h : hits) line.emplace_back(sign * h.t, h.geometricNormal.dot(d) < 0.0);
    }
    std::sort(line.begin(), line.end());
    int last = 0;  // +1 entering, -1 leaving
    bool alternate = true;
    for (size_t k = 0; k < line.size(); ++k) {
      if (k > 0 && line[k].first - line[k - 1].first < merge &&
          line[k].second == line[k - 1].second)
        continue;
      const int dir = line[k].second ? 1 : -1;
      alternate &= last == 0 || dir != last;
      last = dir;
    }
    bad += !alternate;
  }
  return bad;
}

TEST(RobustWatertight, DishedThinPlateKeepsItsFacesApart) {
  // 0.006 thick; the normals of each large face tilted by up to 40° towards a point of it, as
  // for a dish, so its fit sags (or bulges) ~0.4 towards the other face. Closed either way,
  // but without keeping the cells of triangles that share no vertex apart, each large face's
  // sheets crossed the other's: 552 of 100,000 lines saw the surface cross itself.
  const double t = std::tan(40.0 * kPi / 180.0) / std::sqrt(2.0);
  const auto mesh = plate(0.003, [t](const Vec3& p, const Vec3& n) {
    if (n.z() > 0.5) return Vec3(-(p.x() - 0.3) * t, -(p.y() + 0.2) * t, 1);
    if (n.z() < -0.5) return Vec3(-(p.x() - 0.2) * t, -(p.y() - 0.3) * t, -1);
    return n;
  });
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(linesNotAlternating(model, 100000), 0u);
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustWatertight, SliversOfTheGenus2SurfaceKeepTheirNeighboursApart) {
  // The genus-2 surface's mesh has slivers (corners down to 0.9°) and its exact normals. When
  // the edge planes of generic data were turned towards the neighbours' crossing (up to 30°),
  // a sliver's two long edge planes crossed close to the surface at its sharp corner, beyond
  // which the cells of the two triangles along it overlapped: their sheets met nearly
  // coincident there (3 of 1,000,000 lines cracked; 21 of these 100,000 lines saw the surface
  // cross itself).
  const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec("genus2")->mesh);
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(linesNotAlternating(model, 100000), 0u);
}

TEST(RobustWatertight, FaceWhoseNormalsPointInside) {
  const auto mesh = octahedronWithAReversedFace();
  ASSERT_TRUE(MeshTopology(*mesh).isClosed());
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
  // Its patch faces out like the others: the winding, not its normals, says where inside is.
  const RobustImplicitModel model(mesh);
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const Vec3 centre = (mesh->corner(t, 0) + mesh->corner(t, 1) + mesh->corner(t, 2)) / 3.0;
    EXPECT_GT(model.evaluate(t, 1.0 / 3, 1.0 / 3).normal.dot(centre), 0.0) << t;
  }
}

}  // namespace
}  // namespace quadtri

namespace quadtri {
namespace {

std::shared_ptr<const TriangleMesh> withAverageNormals(const char* spec) {
  TriangleMesh mesh = parseBuiltinSpec(spec)->mesh;
  computeVertexNormals(mesh, NormalSource::Average);
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}

TEST(RobustFallback, ACoarseTorusKeepsItsFits) {
  // 8 × 6 quads, averaged normals (~30° from the faces). With slabs sized by a sampled
  // curvature bound (up to a tenth of an edge beyond the patch), the cells reached where the
  // fits' gradients turn, and 8 of its 96 patches fell back to their plane, 8 more to blended
  // normals; slabs grown from tight only while the sheet leaves them keep every fit.
  const auto mesh = withAverageNormals("torus:1,0.5,8,6");
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.flatCount(), 0u);
  EXPECT_EQ(model.blendedCount(), 0u);
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustFallback, FitsThatFoldOnlyWhereTheyAreNotKeepTheirNormals) {
  // A fit is a single sheet, a graph over its triangle, when its gradient has a positive
  // component along the face normal wherever it vanishes in the cell; requiring that at every
  // vertex of the cell instead rejected fits whose gradient turns only far from their sheet:
  // 8 of the L-block's 28 patches took blended normals, then 6 (none its plane); 4 since the
  // rise limit also allows twice the edges' arc sagitta.
  const RobustImplicitModel model(lBlock());
  EXPECT_EQ(model.flatCount(), 0u);
  EXPECT_EQ(model.blendedCount(), 4u);
  EXPECT_EQ(model.fallbackCount(), 4u);
}

TEST(RobustFallback, SliversAlongACurvedDirectionKeepTheirFits) {
  // A thin torus cut into 8 × 16 quads: each triangle is a sliver along the ring. At a sliver's
  // sharp corner its two long edge planes meet in a line close to the triangle's plane, so the
  // cell ran on past the corner, along the ring, where the surface leaves the slab: 80 of the
  // 256 patches fell back. A cap across the corner's bisector ends the cell there: 48.
  const auto mesh =
      std::make_shared<const TriangleMesh>(parseBuiltinSpec("torus:1,0.1,8,16")->mesh);
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.flatCount(), 0u);
  EXPECT_LE(model.fallbackCount(), 48u);
  size_t capped = 0;
  for (const QuadricPatch& p : model.quadricPatches()) capped += p.planeCount == 6;
  EXPECT_GT(capped, 0u);
  EXPECT_EQ(crackedLines(mesh, 100000), 0u);
}

TEST(RobustFallback, FewPatchesOfTheGenus2SurfaceFallBack) {
  // Averaged normals on the genus-2 surface's irregular mesh (5,684 triangles, slivers): one
  // patch falls back to its plane (14 before the tight slabs), under 2% are blended.
  const auto mesh = withAverageNormals("genus2");
  const RobustImplicitModel model(mesh);
  EXPECT_LE(model.flatCount(), 1u);
  EXPECT_LT(double(model.blendedCount()), 0.02 * double(mesh->triangleCount()));
  // Whatever candidate a patch took, its corners are exact (to the round-off of fits on its
  // slivers, 4e-8 of an edge at worst), and a flat one is its plane.
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const QuadricPatch& p = model.quadricPatches()[t];
    const double scale = mesh->meanEdgeLength(t);
    for (int k = 0; k < 3; ++k) {
      const Vec3 x = mesh->corner(t, k);
      EXPECT_LT(std::abs(evalQuadric(p.q, x)) / quadricGradient(p.q, x).norm(), 1e-7 * scale) << t;
    }
    if (model.isFlat(t)) {
      EXPECT_NEAR(quadricGradient(p.q, Vec3::Zero()).norm(), 1.0, 1e-12);
    }
  }
}

}  // namespace
}  // namespace quadtri

namespace quadtri {
namespace {

double pointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (n2 > 0) {
    const Vec3 q = p - (n.dot(p - a) / n2) * n;
    const double wb = (q - a).cross(c - a).dot(n) / n2, wc = (b - a).cross(q - a).dot(n) / n2;
    if (wb >= 0 && wc >= 0 && wb + wc <= 1) return (p - q).norm();
  }
  const auto segment = [&](const Vec3& x, const Vec3& y) {
    const Vec3 d = y - x;
    const double s =
        d.squaredNorm() > 0 ? std::clamp((p - x).dot(d) / d.squaredNorm(), 0.0, 1.0) : 0.0;
    return (p - (x + s * d)).norm();
  };
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// Over every hit of `count` crack-rate-like lines: the largest distance from the hit to the
// nearer of its primitive's triangles (a bridge's two), in that triangle's mean edge lengths.
double farthestHit(const RobustImplicitModel& model, size_t count) {
  const TriangleMesh& m = model.mesh();
  const auto& all = model.renderPatches();
  Accel accel(Accel::Options{true, true});
  addModelGeometry(accel, model, Tessellation{});
  accel.commit();
  Bounds3 box = accel.bounds();
  const double diagonal = box.diagonal().norm();
  box.inflate(0.05 * diagonal);
  double worst = 0.0;
  std::vector<RayHit> hits;
  for (size_t i = 0; i < count; ++i) {
    Pcg32 rng(23, i);
    const Vec3 u(rng.nextDouble(), rng.nextDouble(), rng.nextDouble());
    const Vec3 o = box.lo + box.diagonal().cwiseProduct(u);
    const double z = 1.0 - 2.0 * rng.nextDouble(), phi = 2.0 * kPi * rng.nextDouble();
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    for (double sign : {1.0, -1.0}) {
      hits.clear();
      accel.allHits(Ray{o, sign * d, 0.0, 2.0 * diagonal}, hits);
      for (const RayHit& h : hits) {
        const QuadricPatch& p = all[h.primitive];
        const Vec3 x = o + sign * h.t * d;
        double nearest = kInfinity;
        for (int32_t t : p.isBridge() ? p.joins : std::array<int32_t, 2>{int32_t(h.primitive), -1})
          if (t >= 0)
            nearest = std::min(
                nearest, pointTriangleDistance(x, m.corner(size_t(t), 0), m.corner(size_t(t), 1),
                                               m.corner(size_t(t), 2)) /
                             m.meanEdgeLength(size_t(t)));
        worst = std::max(worst, nearest);
      }
    }
  }
  return worst;
}

TEST(RobustStraySheets, NothingFartherThanHalfAnEdgeFromItsTriangle) {
  // Every sheet lies in its cell, within half its triangle's least altitude of the triangle
  // (sampled) and inside its slab; bridges lie on their cells' faces. The bridge-only design's
  // sheets reached 1.4 mean edge lengths from their triangles on the pyramid (9,899 of its hits
  // of 100,000 lines farther than one).
  for (const auto& mesh : {pyramid(), lBlock(), thinPlate(),
                           std::const_pointer_cast<TriangleMesh>(withAverageNormals("genus2"))}) {
    const RobustImplicitModel model(mesh);
    EXPECT_LT(farthestHit(model, 20000), 0.5) << mesh->triangleCount();
  }
}

}  // namespace
}  // namespace quadtri
