#include <fmt/format.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/mesh/mesh_io.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/implicit_fit.h"
#include "quadtri/surface/implicit_model.h"
#include "quadtri/surface/model.h"

namespace quadtri {
namespace {

const double kPhi = (1.0 + std::sqrt(5.0)) / 2.0;
// Circumradius of the icosahedron with vertices (0, ±1, ±φ) and their cyclic permutations.
const double kStandardRadius = std::sqrt(1.0 + kPhi * kPhi);

std::shared_ptr<TriangleMesh> scaledIcosahedron(double scale) {
  auto m = std::make_shared<TriangleMesh>(makeBuiltin("icosahedron").mesh);
  for (Vec3& p : m->positions) p *= scale;
  return m;
}

double longestEdge(const QuadraticPatch& fp) {
  return std::max(
      {(fp.v[1] - fp.v[0]).norm(), (fp.v[2] - fp.v[1]).norm(), (fp.v[0] - fp.v[2]).norm()});
}

// f_p's unit normal at (u,v), oriented to the shading normals.
Vec3 parametricNormal(const ImplicitModel& model, size_t t, double u, double v) {
  Vec3 du, dv;
  model.parametricPatch(t).derivatives(u, v, du, dv);
  return patchOrientation(model.mesh(), t) * du.cross(dv).normalized();
}

TEST(ImplicitModel, IcosahedronFitIsNearButNotTheCircumscribedSphere) {
  // docs/DESIGN.md §3: on the standard icosahedron (circumradius 1.902) the thesis' least squares
  // gives J/A = -3.13, where the circumscribed sphere x²+y²+z² - r² has -r² = -3.62. Face 0
  // (the one whose quadric has A = B = C) is the one compared.
  const ImplicitModel model(scaledIcosahedron(kStandardRadius));
  const QuadricCoeffs& q = model.quadricPatches()[0].q;
  EXPECT_NEAR(q[1] / q[0], 1.0, 1e-9);
  EXPECT_NEAR(q[2] / q[0], 1.0, 1e-9);
  EXPECT_NEAR(q[9] / q[0], -3.1324, 0.005);
  EXPECT_GT(std::abs(q[9] / q[0] + kStandardRadius * kStandardRadius), 0.4);
  // Eq. 4.13 is one row of a least-squares system that the other rows can satisfy exactly
  // here, so it holds exactly.
  double sum = 0.0;
  for (double c : q) sum += c;
  EXPECT_NEAR(sum, 1.0, 1e-9);
}

TEST(ImplicitModel, IcosahedronPatchesAreCongruent) {
  // Every face of a regular icosahedron is a rotation of face 0 about the origin, so the
  // rotation invariants of the fitted quadric (eigenvalues of its quadratic form and the
  // length of its linear part, both relative to J) agree across faces.
  const ImplicitModel model(scaledIcosahedron(kStandardRadius));
  auto invariants = [&](size_t t) {
    const QuadricCoeffs& q = model.quadricPatches()[t].q;
    Mat3 form;
    form << q[0], q[3] / 2, q[4] / 2, q[3] / 2, q[1], q[5] / 2, q[4] / 2, q[5] / 2, q[2];
    const Eigen::SelfAdjointEigenSolver<Mat3> solver(form / q[9]);
    const Vec3 eig = solver.eigenvalues();
    return Vec4(eig[0], eig[1], eig[2], Vec3(q[6], q[7], q[8]).norm() / std::abs(q[9]));
  };
  const Vec4 ref = invariants(0);
  for (size_t t = 1; t < model.patchCount(); ++t)
    EXPECT_LT((invariants(t) - ref).norm(), 1e-9 * ref.norm()) << "face " << t;
}

// Largest first-order corner distance |f(v)|/|∇f(v)| (relative to the longest edge) and angle
// between the oriented gradient and the shading normal at the corners, over all patches.
std::pair<double, double> cornerErrors(const ImplicitModel& model) {
  double maxDistance = 0.0, maxAngle = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadricPatch& patch = model.quadricPatches()[t];
    const double edge = longestEdge(model.parametricPatch(t));
    for (int k = 0; k < 3; ++k) {
      const Vec3& v = model.mesh().corner(t, k);
      const Vec3 grad = quadricGradient(patch.q, v);
      maxDistance = std::max(maxDistance, std::abs(evalQuadric(patch.q, v)) / grad.norm() / edge);
      maxAngle = std::max(maxAngle,
                          angleDegrees(patch.orientation * grad, model.mesh().cornerNormal(t, k)));
    }
  }
  return {maxDistance, maxAngle};
}

TEST(ImplicitModel, CornersLieNearTheQuadricWithNearlyTheShadingNormal) {
  // On the icosahedron the 12 homogeneous rows are consistent, so corners and normals are
  // exact to round-off. On the ellipsoid they conflict and the least squares holds neither
  // exactly (docs/DESIGN.md §3); measured there: distance 0.0018 of an edge, angle 0.053°.
  const auto [icoDistance, icoAngle] =
      cornerErrors(ImplicitModel(scaledIcosahedron(kStandardRadius)));
  EXPECT_LT(icoDistance, 1e-12);
  EXPECT_LT(icoAngle, 1e-6);
  const auto [distance, angle] =
      cornerErrors(ImplicitModel(std::make_shared<TriangleMesh>(makeBuiltin("ellipsoid").mesh)));
  RecordProperty("ellipsoid_corner_distance_over_edge", fmt::format("{:.3g}", distance));
  RecordProperty("ellipsoid_corner_normal_angle_deg", fmt::format("{:.3g}", angle));
  EXPECT_GT(distance, 1e-3);
  EXPECT_LT(distance, 4e-3);
  EXPECT_GT(angle, 0.02);
  EXPECT_LT(angle, 0.1);
}

TEST(ImplicitModel, RaysTowardTheBarycentreHitNearIt) {
  const ImplicitModel model(scaledIcosahedron(kStandardRadius));
  double maxOffset = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadricPatch& patch = model.quadricPatches()[t];
    const Vec3 c = model.parametricPatch(t).position(1.0 / 3, 1.0 / 3);
    const Vec3 n = parametricNormal(model, t, 1.0 / 3, 1.0 / 3);
    const double edge = longestEdge(model.parametricPatch(t));
    const Vec3 origin = c + 2.0 * edge * n;
    double tHit = 0.0;
    ASSERT_TRUE(intersectQuadricPatch(patch, origin, -n, 0.0, kInfinity, tHit)) << "face " << t;
    const Vec3 hit = origin - tHit * n;
    maxOffset = std::max(maxOffset, (hit - c).norm() / edge);
    // The hit's normal faces the ray's origin (the shading normals' side).
    EXPECT_GT((patch.orientation * quadricGradient(patch.q, hit)).dot(n), 0.99) << "face " << t;
  }
  RecordProperty("barycentre_hit_offset_over_edge", fmt::format("{:.3g}", maxOffset));
  // Row 4.12 holds exactly here (the system is consistent): the hit is f_p(1/3,1/3) itself.
  EXPECT_LT(maxOffset, 1e-12);
}

// λ0 = 1 - u - v of the point of triangle t's plane nearest to p.
double lambda0(const TriangleMesh& mesh, size_t t, const Vec3& p) {
  Eigen::Matrix<double, 3, 2> edges;
  edges << mesh.corner(t, 1) - mesh.corner(t, 0), mesh.corner(t, 2) - mesh.corner(t, 0);
  const Eigen::Vector2d uv = edges.colPivHouseholderQr().solve(p - mesh.corner(t, 0));
  return 1.0 - uv.sum();
}

TEST(ImplicitModel, BoundsHoldThePatchOverItsDomain) {
  // The bounds come from an 8×8 lattice plus a 5% margin; a 40×40 lattice of the projected
  // patch, where the planes keep it, must lie inside them.
  for (const char* shape : {"icosahedron", "ellipsoid"}) {
    const ImplicitModel model(std::make_shared<TriangleMesh>(makeBuiltin(shape).mesh));
    size_t kept = 0;
    for (size_t t = 0; t < model.patchCount(); ++t) {
      const QuadricPatch& patch = model.quadricPatches()[t];
      for (int i = 0; i <= 40; ++i)
        for (int j = 0; i + j <= 40; ++j) {
          const Vec3 p = model.evaluate(t, i / 40.0, j / 40.0).position;
          if (!patch.inside(p)) continue;
          ++kept;
          EXPECT_TRUE((p.array() >= patch.bounds.lo.array()).all() &&
                      (p.array() <= patch.bounds.hi.array()).all())
              << shape << " face " << t << " at " << i << "," << j;
        }
    }
    EXPECT_GT(kept, model.patchCount() * 600) << shape;  // of 861 lattice points per patch
  }
}

TEST(ImplicitModel, ThesisPlaneFourLeavesEdgeOneToTheBounds) {
  // Plane (4) passes through f_p(1,1), outside the domain, so it does not follow edge 1
  // (corners 1-2): on the icosahedron it trims the patch up to λ0 = 0.1 inside that edge and
  // leaves a sliver of the cap beyond it (λ0 < 0), which only the bounds cut off. Every point
  // of the plane-clipped sheet outside the bounds lies beyond edge 1.
  const ImplicitModel model(std::make_shared<TriangleMesh>(makeBuiltin("icosahedron").mesh));
  double trimmedDepth = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const Vec4& plane4 = model.quadricPatches()[t].planes[3];
    for (int i = 0; i <= 40; ++i)
      for (int j = 0; i + j <= 40; ++j) {
        const Vec3 p = model.evaluate(t, i / 40.0, j / 40.0).position;
        if (plane4.head<3>().dot(p) + plane4[3] < 0.0)
          trimmedDepth = std::max(trimmedDepth, 1.0 - (i + j) / 40.0);
      }
  }
  EXPECT_NEAR(trimmedDepth, 0.1, 0.03);

  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> uni(-1.0, 1.0);
  size_t outside = 0, hits = 0;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadricPatch& patch = model.quadricPatches()[t];
    ASSERT_EQ(patch.planeCount, 4);
    QuadricPatch unbounded = patch;
    unbounded.bounds.extend(Vec3::Constant(1e300));
    unbounded.bounds.extend(Vec3::Constant(-1e300));
    const double edge = longestEdge(model.parametricPatch(t));
    for (int i = 0; i < 500; ++i) {
      const Vec3 target = patch.bounds.center() +
                          patch.bounds.diagonal().cwiseProduct(Vec3(uni(rng), uni(rng), uni(rng)));
      const Vec3 d = Vec3(uni(rng), uni(rng), uni(rng)).normalized();
      const Vec3 o = target - 3.0 * edge * d;
      double tHit = 0.0;
      if (intersectQuadricPatch(patch, o, d, 0.0, kInfinity, tHit)) {
        const Vec3 h = o + tHit * d;
        EXPECT_TRUE((h.array() >= patch.bounds.lo.array()).all() &&
                    (h.array() <= patch.bounds.hi.array()).all());
      }
      if (!intersectQuadricPatch(unbounded, o, d, 0.0, kInfinity, tHit)) continue;
      ++hits;
      const Vec3 h = o + tHit * d;
      if ((h.array() >= patch.bounds.lo.array()).all() &&
          (h.array() <= patch.bounds.hi.array()).all())
        continue;
      ++outside;
      EXPECT_LT(lambda0(model.mesh(), t, h), 0.0) << "face " << t;
    }
  }
  RecordProperty("plane_clipped_hits_outside_bounds", std::to_string(outside));
  EXPECT_GT(hits, 1000u);
  EXPECT_GT(outside, 10u);
}

TEST(ImplicitModel, EvaluateProjectsOntoTheQuadricAndKeepsCorners) {
  const ImplicitModel model(scaledIcosahedron(kStandardRadius));
  double maxOffset = 0.0;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadricPatch& patch = model.quadricPatches()[t];
    const double edge = longestEdge(model.parametricPatch(t));
    for (int i = 0; i <= 6; ++i)
      for (int j = 0; i + j <= 6; ++j) {
        const double u = i / 6.0, v = j / 6.0;
        const SurfacePoint sp = model.evaluate(t, u, v);
        const Vec3 grad = quadricGradient(patch.q, sp.position);
        EXPECT_LT(std::abs(evalQuadric(patch.q, sp.position)) / grad.norm(), 1e-12 * edge);
        EXPECT_NEAR(sp.normal.dot(patch.orientation * grad.normalized()), 1.0, 1e-12);
        // The move from f_p is along f_p's normal and small.
        const Vec3 offset = sp.position - model.parametricPatch(t).position(u, v);
        maxOffset = std::max(maxOffset, offset.norm() / edge);
        EXPECT_LT(offset.cross(parametricNormal(model, t, u, v)).norm(), 1e-12 * edge);
      }
    for (int k = 0; k < 3; ++k) {
      const double uv[3][2] = {{0, 0}, {1, 0}, {0, 1}};
      const SurfacePoint sp = model.evaluate(t, uv[k][0], uv[k][1]);
      EXPECT_LT((sp.position - model.mesh().corner(t, k)).norm(), 1e-12 * edge);
      EXPECT_LT(angleDegrees(sp.normal, model.mesh().cornerNormal(t, k)), 1e-6);
    }
  }
  RecordProperty("max_offset_from_parametric_over_edge", fmt::format("{:.3g}", maxOffset));
  EXPECT_GT(maxOffset, 1e-4);
  EXPECT_LT(maxOffset, 0.02);
}

TEST(ImplicitModel, FlatInputGivesThePlaneTriangle) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {Vec3(0.2, 0.1, 1.0), Vec3(1.4, 0.3, 0.8), Vec3(0.5, 1.1, 1.3)};
  mesh->triangles = {{0, 1, 2}};
  mesh->normals = {mesh->faceNormal(0)};
  mesh->normalIndices = {{0, 0, 0}};
  const ImplicitModel model(mesh);
  const QuadricPatch& patch = model.quadricPatches()[0];
  for (int i = 0; i < 6; ++i) EXPECT_EQ(patch.q[i], 0.0);
  const Vec3 n(patch.q[6], patch.q[7], patch.q[8]);
  EXPECT_NEAR(std::abs(n.normalized().dot(mesh->faceNormal(0))), 1.0, 1e-12);
  double sum = 0.0;
  for (double c : patch.q) sum += c;
  EXPECT_NEAR(sum, 1.0, 1e-12);  // eq. 4.13 still holds
  // The corner plane is dropped (it holds the patch); the other three cut along the edges.
  EXPECT_EQ(patch.planeCount, 3);
  const Vec3 fn = mesh->faceNormal(0);
  const Vec3 centroid = (mesh->corner(0, 0) + mesh->corner(0, 1) + mesh->corner(0, 2)) / 3.0;
  double tHit = 0.0;
  ASSERT_TRUE(intersectQuadricPatch(patch, centroid + fn, -fn, 0.0, kInfinity, tHit));
  EXPECT_NEAR(tHit, 1.0, 1e-12);
  // Just outside each edge, the edge planes reject the hit; just inside, they keep it.
  for (int k = 0; k < 3; ++k) {
    const Vec3 mid = 0.5 * (mesh->corner(0, k) + mesh->corner(0, (k + 1) % 3));
    const Vec3 out = (mid - centroid).normalized() * 1e-6;
    EXPECT_FALSE(intersectQuadricPatch(patch, mid + out + fn, -fn, 0.0, kInfinity, tHit)) << k;
    EXPECT_TRUE(intersectQuadricPatch(patch, mid - out + fn, -fn, 0.0, kInfinity, tHit)) << k;
  }
  const SurfacePoint sp = model.evaluate(0, 0.25, 0.5);
  EXPECT_LT((sp.position -
             (0.25 * mesh->corner(0, 0) + 0.25 * mesh->corner(0, 1) + 0.5 * mesh->corner(0, 2)))
                .norm(),
            1e-12);
  EXPECT_NEAR(sp.normal.dot(fn), 1.0, 1e-12);
}

void expectFiniteJson(const nlohmann::json& j, const std::string& where) {
  if (j.is_number()) {
    EXPECT_TRUE(std::isfinite(j.get<double>())) << where;
  } else if (j.is_structured()) {
    for (const auto& item : j.items()) expectFiniteJson(item.value(), where + "/" + item.key());
  }
}

void expectFiniteModel(const std::shared_ptr<TriangleMesh>& mesh, const std::string& what) {
  const ImplicitModel model(mesh);
  for (size_t t = 0; t < model.patchCount(); ++t) {
    const QuadricPatch& patch = model.quadricPatches()[t];
    for (double c : patch.q) EXPECT_TRUE(std::isfinite(c)) << what;
    EXPECT_TRUE(allFinite(patch.bounds.lo) && allFinite(patch.bounds.hi)) << what;
    for (int i = 0; i < patch.planeCount; ++i)
      EXPECT_TRUE(patch.planes[i].allFinite()) << what << " plane " << i;
    expectFiniteJson(model.patchJson(t), what);
    for (int i = 0; i <= 4; ++i)
      for (int j = 0; i + j <= 4; ++j) {
        const SurfacePoint sp = model.evaluate(t, i / 4.0, j / 4.0);
        EXPECT_TRUE(allFinite(sp.position)) << what;
        EXPECT_NEAR(sp.normal.norm(), 1.0, 1e-12) << what;
      }
  }
}

std::shared_ptr<TriangleMesh> oneTriangle(const std::array<Vec3, 3>& p,
                                          const std::array<Vec3, 3>& n) {
  auto mesh = std::make_shared<TriangleMesh>();
  mesh->positions = {p[0], p[1], p[2]};
  mesh->triangles = {{0, 1, 2}};
  mesh->normals = {n[0].normalized(), n[1].normalized(), n[2].normalized()};
  mesh->normalIndices = {{0, 1, 2}};
  return mesh;
}

TEST(ImplicitModel, DegenerateInputsStayFinite) {
  const Vec3 z(0, 0, 1);
  const std::array<Vec3, 3> tri = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)};
  expectFiniteModel(oneTriangle({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0)},
                                {z, Vec3(0.3, 0, 1), Vec3(0, 0.2, 1)}),
                    "collinear corners");
  expectFiniteModel(oneTriangle({Vec3(1, 1, 1), Vec3(1, 1, 1), Vec3(1, 1, 1)},
                                {z, Vec3(0.3, 0, 1), Vec3(0, 0.2, 1)}),
                    "coincident corners");
  expectFiniteModel(oneTriangle(tri, {z, z, z}), "identical normals");
  expectFiniteModel(oneTriangle(tri, {z, Vec3(-z), z}), "opposite normals");
  expectFiniteModel(oneTriangle(tri, {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(-1, -1, 0.01)}),
                    "normals in the triangle's plane");

  // A zero normal in a file is replaced by the face normal at load.
  const auto path = std::filesystem::temp_directory_path() /
                    ("quadtri_implicit_zero_normal_" + std::to_string(::getpid()) + ".obj");
  {
    std::ofstream obj(path);
    obj << "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.2\n"
        << "vn 0 0 0\nvn 0.2 0 1\nvn 0 0.3 1\nvn 0.1 0.1 1\n"
        << "f 1//1 2//2 3//3\nf 2//2 4//4 3//3\n";
  }
  auto loaded = std::make_shared<TriangleMesh>(loadMesh(path));
  std::filesystem::remove(path);
  ASSERT_EQ(loaded->triangleCount(), 2u);
  expectFiniteModel(loaded, "zero normal in a file");
}

TEST(ImplicitModel, IcosahedronFitScalesWithTheMesh) {
  // On the icosahedron the 12 homogeneous rows (eq. 4.10-4.12) have an exact one-dimensional
  // solution space, so row 4.13 only sets its scale and the fit is the scaled fit exactly:
  // J/(A r²) is the same at every scale. The non-scale-freeness needs an inconsistent system.
  double reference = 0.0;
  for (double scale : {1e-3, 1.0, 1e3}) {
    const ImplicitModel model(scaledIcosahedron(scale));
    const QuadricCoeffs& q = model.quadricPatches()[0].q;
    const double ratio = q[9] / (q[0] * scale * scale);
    if (scale == 1e-3) reference = ratio;
    EXPECT_NEAR(ratio, reference, 1e-7) << scale;
    EXPECT_NEAR(ratio, -3.1324 / (kStandardRadius * kStandardRadius), 0.005) << scale;
  }
}

TEST(ImplicitModel, FitIsNotScaleFreeWhereTheRowsConflict) {
  // On an ellipsoid the rows conflict, and row 4.13 (A+…+J = 1) weighs against monomial
  // columns that scale as s², s and 1: the same mesh in other units gets a differently shaped
  // quadric. Coefficients of the 1e3-scaled fit are mapped back to unit coordinates and
  // compared with the unit fit as directions in R^10.
  const auto mesh = std::make_shared<TriangleMesh>(makeBuiltin("ellipsoid").mesh);
  auto scaled = std::make_shared<TriangleMesh>(*mesh);
  const double s = 1e3;
  for (Vec3& p : scaled->positions) p *= s;
  const ImplicitModel unit(mesh), big(scaled);
  double maxAngle = 0.0, unitCorner = 0.0, bigCorner = 0.0;
  const double columnScale[10] = {s * s, s * s, s * s, s * s, s * s, s * s, s, s, s, 1};
  for (size_t t = 0; t < unit.patchCount(); ++t) {
    Eigen::Matrix<double, 10, 1> a, b;
    for (int i = 0; i < 10; ++i) {
      a[i] = unit.quadricPatches()[t].q[i];
      b[i] = big.quadricPatches()[t].q[i] * columnScale[i];
    }
    const double cosine = std::abs(a.normalized().dot(b.normalized()));
    maxAngle = std::max(maxAngle, std::acos(std::min(1.0, cosine)) * 180.0 / kPi);
    for (int k = 0; k < 3; ++k) {
      auto firstOrder = [&](const ImplicitModel& m, double size) {
        const QuadricCoeffs& q = m.quadricPatches()[t].q;
        const Vec3& v = m.mesh().corner(t, k);
        return std::abs(evalQuadric(q, v)) / quadricGradient(q, v).norm() / size;
      };
      unitCorner = std::max(unitCorner, firstOrder(unit, 1.0));
      bigCorner = std::max(bigCorner, firstOrder(big, s));
    }
  }
  RecordProperty("coefficient_angle_deg", fmt::format("{:.3g}", maxAngle));
  RecordProperty("corner_distance_unit", fmt::format("{:.3g}", unitCorner));
  RecordProperty("corner_distance_scaled", fmt::format("{:.3g}", bigCorner));
  EXPECT_GT(maxAngle, 1.0);
  EXPECT_GT(std::abs(unitCorner - bigCorner), 0.2 * unitCorner);
}

TEST(ImplicitModel, RegisteredAsQuadricImplicit) {
  const auto& names = modelNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "quadric-implicit"), names.end());
  auto mesh = std::make_shared<const TriangleMesh>(makeBuiltin("icosahedron").mesh);
  const auto model = makeModel("quadric-implicit", mesh);
  EXPECT_EQ(model->name(), "quadric-implicit");
  EXPECT_EQ(model->representation(), Representation::Implicit);
  ASSERT_EQ(model->quadricPatches().size(), mesh->triangleCount());
  EXPECT_EQ(model->patchMemoryBytes(), sizeof(QuadricPatch) * mesh->triangleCount());
  const nlohmann::json j = model->patchJson(3);
  const QuadricPatch& patch = model->quadricPatches()[3];
  ASSERT_EQ(j["quadric"].size(), 10u);
  for (int i = 0; i < 10; ++i) EXPECT_EQ(j["quadric"][i].get<double>(), patch.q[i]);
  ASSERT_EQ(j["planes"].size(), size_t(patch.planeCount));
  EXPECT_EQ(j["planes"][1][3].get<double>(), patch.planes[1][3]);
  EXPECT_EQ(j["bounds"]["min"][2].get<double>(), patch.bounds.lo.z());
  EXPECT_EQ(j["bounds"]["max"][0].get<double>(), patch.bounds.hi.x());
  ASSERT_EQ(j["coefficients"].size(), 6u);
  const auto* implicit = dynamic_cast<const ImplicitModel*>(model.get());
  ASSERT_NE(implicit, nullptr);
  EXPECT_EQ(j["coefficients"]["c0"][1].get<double>(), implicit->parametricPatch(3).v[0].y());
  ASSERT_EQ(j["control_points"].size(), 3u);
  EXPECT_EQ(j["control_points"]["b20"][0].get<double>(), implicit->parametricPatch(3).b[2].x());
  EXPECT_EQ(j["orientation"].get<double>(), patch.orientation);
}

}  // namespace
}  // namespace quadtri
