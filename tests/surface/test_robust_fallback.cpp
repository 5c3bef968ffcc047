// The robust implicit model's fallback chain on configurations from the corpus where patches
// gave up their corner normals although nothing required it (docs/DESIGN.md §3.7 (h)). Each
// test failed before the change its comment names.
#include <gtest/gtest.h>

#include <cmath>

#include "quadtri/analysis/crack_rate.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/robust_implicit_model.h"

namespace quadtri {
namespace {

// A mesh from positions, triangles, normals and per-corner normal indices.
std::shared_ptr<const TriangleMesh> meshOf(std::vector<Vec3> positions, std::vector<Tri> triangles,
                                           std::vector<Vec3> normals,
                                           std::vector<Tri> normalIndices) {
  TriangleMesh mesh;
  mesh.positions = std::move(positions);
  mesh.triangles = std::move(triangles);
  mesh.normals = std::move(normals);
  for (Vec3& n : mesh.normals) n.normalize();
  mesh.normalIndices = std::move(normalIndices);
  return std::make_shared<const TriangleMesh>(std::move(mesh));
}

TEST(RobustFallback, SliversAtAConeApexKeepTheirNormals) {
  // The apex of CGAL's mask_cone.off: a fan of 30 slivers (12° at the apex) whose apex normal
  // is the axis and whose rim normals are the cone's, 45° from it. The fits rise about 0.69 of
  // their least altitude over their triangles, and the rise limit of half the altitude sent
  // all 30 to blended normals. The limit is now also twice the largest sagitta of the edges'
  // arcs, which the normals set.
  constexpr int kSegments = 30;
  std::vector<Vec3> positions{Vec3(0, 0, 1)};
  std::vector<Vec3> normals{Vec3(0, 0, 1)};
  std::vector<Tri> triangles;
  for (int i = 0; i < kSegments; ++i) {
    const double phi = 2.0 * kPi * i / kSegments;
    positions.emplace_back(std::cos(phi), std::sin(phi), 0.0);
    normals.emplace_back(std::cos(phi), std::sin(phi), 1.0);
    triangles.push_back({0u, uint32_t(1 + i), uint32_t(1 + (i + 1) % kSegments)});
  }
  const auto mesh = meshOf(positions, triangles, normals, triangles);
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.fallbackCount(), 0u);
  EXPECT_EQ(model.flatCount(), 0u);
  // Each patch rises more than half its least altitude, and less than a quarter of its long
  // edge.
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    const Vec3 n = mesh->faceNormal(t);
    const Vec3 apex = mesh->corner(t, 0);
    const double longEdge = (mesh->corner(t, 1) - apex).norm();
    double rise = 0.0;
    for (int j = 0; j <= 8; ++j)
      for (int i = 0; i + j <= 8; ++i)
        rise = std::max(rise, std::abs(n.dot(model.evaluate(t, i / 8.0, j / 8.0).position - apex)));
    EXPECT_GT(rise, 0.5 * mesh->faceCross(t).norm() / longEdge) << t;
    EXPECT_LT(rise, 0.25 * longEdge) << t;
  }
}

TEST(RobustFallback, ThinRingKeepsItsNormalsThroughMembersOfThePencil) {
  // A thin torus (R = 1, r = 0.02) of 96 segments and 3 rings: a tube of triangular section
  // whose corner normals turn 120° across each face. A third of the fits (and their graph
  // members) left the checks of their cells, and those patches took blended normals, 30° off
  // the shading normals at their corners. Members q + μL² of the fit's pencil, which keep the
  // corners and their normals, now pass for every one of them.
  ShapeParams params;
  params.major = 1.0;
  params.minor = 0.02;
  params.segments = 96;
  params.rings = 3;
  const auto mesh = std::make_shared<const TriangleMesh>(makeBuiltin("torus", params).mesh);
  ASSERT_EQ(mesh->triangleCount(), 576u);
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.fallbackCount(), 0u);
  EXPECT_EQ(model.blendedCount(), 0u);
  EXPECT_EQ(model.flatCount(), 0u);
  for (size_t t = 0; t < mesh->triangleCount(); ++t) {
    EXPECT_EQ(model.blend(t), 0.0) << t;
    EXPECT_LT(model.cornerNormalErrorDeg(t), 0.2) << t;
  }
  // Still watertight.
  CrackRateOptions lines;
  lines.lines = 20000;
  EXPECT_EQ(crackRate(modelGeometry(model, Tessellation{}), lines), 0.0);
}

TEST(RobustFallback, CellsOfTrianglesFacingTheSameWayMayOverlap) {
  // The 21 triangles of CGAL's pig.stl that share a vertex with its triangles 16020 and 16798
  // (here 4 and 15), with their normals: the two share no vertex and face within 8° of each
  // other across a sliver. Their cores overlapped, so both had their reach halved and fell
  // back to blended normals (326 patches of the whole pig, 1.9%). Overlaps matter between
  // sheets that face each other across a thin part; cells of triangles that face within 60°
  // of each other are no longer compared.
  const auto mesh = meshOf(
      {
          Vec3{10.126700401306152, 0.79799997806549072, 14.788000106811523},
          Vec3{10.292200088500977, 0.80830001831054688, 17.144100189208984},
          Vec3{9.0202999114990234, 1.8301999568939209, 15.894399642944336},
          Vec3{9.1548004150390625, 1.8645999431610107, 18.096000671386719},
          Vec3{10.826700210571289, 0.87099999189376831, 19.853700637817383},
          Vec3{9.555999755859375, 2.025399923324585, 20.469499588012695},
          Vec3{8.1823997497558594, 3.1930999755859375, 16.7322998046875},
          Vec3{8.2552995681762695, 3.2432000637054443, 18.814599990844727},
          Vec3{7.6876997947692871, 4.7242999076843262, 17.226999282836914},
          Vec3{9.0302000045776367, 1.8457000255584717, 14.970100402832031},
          Vec3{9.5317001342773438, 1.3106000423431396, 14.43220043182373},
          Vec3{9.5474004745483398, 1.264799952507019, 15.367400169372559},
          Vec3{8.5944995880126953, 2.4644999504089355, 15.348799705505371},
          Vec3{8.6669998168945312, 2.4640998840332031, 14.401800155639648},
          Vec3{8.5613002777099609, 2.4793999195098877, 16.353399276733398},
          Vec3{8.3302001953125, 3.1182000637054443, 14.690899848937988},
          Vec3{8.225799560546875, 3.1635000705718994, 15.706899642944336},
          Vec3{8.0523004531860352, 3.848599910736084, 14.969499588012695},
          Vec3{7.9348998069763184, 3.9168999195098877, 16.00160026550293},
          Vec3{7.8905000686645508, 3.9489998817443848, 17.024200439453125},
      },
      {
          {0, 1, 2},    {1, 3, 2},    {1, 4, 3},    {4, 5, 3},    {2, 3, 6},   {3, 7, 6},
          {3, 5, 7},    {6, 7, 8},    {9, 10, 2},   {10, 11, 2},  {9, 12, 13}, {9, 2, 12},
          {2, 14, 12},  {13, 12, 15}, {12, 16, 15}, {12, 14, 16}, {14, 6, 16}, {15, 16, 17},
          {16, 18, 17}, {16, 6, 18},  {6, 19, 18},
      },
      {
          Vec3{-0.4974559947153836, -0.86678413919592512, 0.034968405169630866},
          Vec3{-0.52497739539160015, -0.84726861934358999, 0.080837002687249374},
          Vec3{-0.72149740565035747, -0.69031814015786441, 0.053873546465690661},
          Vec3{-0.72863136701809184, -0.67666281752751922, 0.10594225961846386},
          Vec3{-0.4842758016349008, -0.85534532197576085, 0.18401447803109411},
          Vec3{-0.67925109092785541, -0.68521348195644838, 0.26286962475424652},
          Vec3{-0.88201184478130745, -0.46874751694382122, 0.048279095108303458},
          Vec3{-0.87362865852017846, -0.47529795588594304, 0.10423444796648339},
          Vec3{-0.97258598897053283, -0.23147214325411497, 0.022296657945909369},
          Vec3{-0.7895707453877463, -0.6123575251218224, -0.039953716404302918},
          Vec3{-0.70377454018452767, -0.70868899908603644, -0.04961148216379422},
          Vec3{-0.79781101390114151, -0.60260768317793378, -0.019014896080591849},
          Vec3{-0.7117779137164717, -0.70203363744481051, -0.022824842637685992},
          Vec3{-0.86305134667053174, -0.50319633005279218, -0.04399802758741593},
          Vec3{-0.87320939793138053, -0.47823938335874999, -0.093768009304658187},
          Vec3{-0.86822929032129215, -0.49567444180484416, -0.022016974579657258},
          Vec3{-0.92369263002563906, -0.36802915827738575, -0.10651978170254101},
          Vec3{-0.91776020657792123, -0.39368337086943972, -0.052245638314854098},
          Vec3{-0.92063301689262855, -0.3894398556996565, -0.027774934739938046},
          Vec3{-0.95601376978492558, -0.26709086615865263, -0.12124413881188682},
          Vec3{-0.95520981664454518, -0.28962558064597071, -0.060755487170943201},
          Vec3{-0.95741095966015821, -0.28699170775620414, -0.031622997988683621},
      },
      {
          {0, 1, 2},    {1, 3, 2},    {1, 4, 3},    {4, 5, 3},    {2, 3, 6},    {3, 7, 6},
          {3, 5, 7},    {6, 7, 8},    {9, 10, 11},  {10, 12, 11}, {9, 13, 14},  {9, 11, 13},
          {11, 15, 13}, {14, 13, 16}, {13, 17, 16}, {13, 15, 17}, {15, 18, 17}, {16, 17, 19},
          {17, 20, 19}, {17, 18, 20}, {18, 21, 20},
      });
  ASSERT_EQ(mesh->triangleCount(), 21u);
  EXPECT_GT(mesh->faceNormal(4).dot(mesh->faceNormal(15)), 0.99);
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.fallbackCount(), 0u);
}

TEST(RobustFallback, SeparatePartsMayComeWithinReachOfEachOther) {
  // Two unit icospheres (level 1, their exact normals) 0.01 apart: the patches facing each other
  // reach 0.05 towards the other sphere, so their cores overlapped and, as across a thin part,
  // were shrunk to blended normals (CGAL's bones.off: different bones within 0.02 to 0.1 edge
  // lengths of each other, 3.4% of its patches). Separate parts are separate solids: their cores
  // are no longer compared. Each sphere keeps its exact patches and the pair stays watertight.
  ShapeParams params;
  params.level = 1;
  const TriangleMesh one = makeBuiltin("icosphere", params).mesh;
  TriangleMesh two = one;
  const size_t offset = two.positions.size(), normalOffset = two.normals.size();
  for (const Vec3& p : one.positions) two.positions.push_back(p + Vec3(2.01, 0.0, 0.0));
  for (const Vec3& n : one.normals) two.normals.push_back(n);
  for (const Tri& t : one.triangles)
    two.triangles.push_back(
        {uint32_t(t[0] + offset), uint32_t(t[1] + offset), uint32_t(t[2] + offset)});
  for (const Tri& t : one.normalIndices)
    two.normalIndices.push_back({uint32_t(t[0] + normalOffset), uint32_t(t[1] + normalOffset),
                                 uint32_t(t[2] + normalOffset)});
  const auto mesh = std::make_shared<const TriangleMesh>(std::move(two));
  const RobustImplicitModel model(mesh);
  EXPECT_EQ(model.fallbackCount(), 0u);
  CrackRateOptions options;
  options.lines = 100000;
  EXPECT_EQ(crackRate(modelGeometry(model, Tessellation{}), options), 0.0);
}

}  // namespace
}  // namespace quadtri
