// Bézier pieces as Embree user geometry: the Accel agrees with the direct intersector, closed
// surfaces of pieces have no cracks, and RenderScene shades their hits.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "fixtures/bezier_pieces.h"
#include "fixtures/sanitized.h"
#include "quadtri/analysis/crack_rate.h"
#include "quadtri/geometry/accel.h"
#include "quadtri/geometry/model_geometry.h"
#include "quadtri/geometry/rng.h"
#include "quadtri/math/error.h"
#include "quadtri/render/bsdf/diffuse.h"
#include "quadtri/render/render_scene.h"

namespace quadtri {
namespace {

// Every edge of every piece is some other piece's edge, run the other way, with bitwise equal
// control points (the closed fixtures rely on it).
bool edgesShared(const std::vector<BezierTriangle>& pieces) {
  for (size_t a = 0; a < pieces.size(); ++a)
    for (int ea = 0; ea < 3; ++ea) {
      bool found = false;
      for (size_t b = 0; b < pieces.size() && !found; ++b)
        for (int eb = 0; eb < 3 && !found; ++eb) {
          if (a == b) continue;
          bool same = true;
          for (int m = 0; m <= 4; ++m)
            same &= pieces[a].b[size_t(fixtures::edgeIndex(ea, m))] ==
                    pieces[b].b[size_t(fixtures::edgeIndex(eb, 4 - m))];
          found = same;
        }
      if (!found) return false;
    }
  return true;
}

// A few curved pieces scattered in space, and a paraboloid.
std::vector<BezierTriangle> scatteredPieces() {
  Pcg32 rng(31);
  std::vector<BezierTriangle> pieces;
  for (int i = 0; i < 12; ++i) {
    const Vec3 base(2.0 * rng.nextDouble(), 2.0 * rng.nextDouble(), 2.0 * rng.nextDouble());
    BezierTriangle piece = fixtures::bumpyPiece(base, base + Vec3(0.8, 0.1, 0.2),
                                                base + Vec3(0.1, 0.7, -0.1), 0.3, rng);
    piece.orientation = i % 2 ? 1.0 : -1.0;
    piece.triangle = uint32_t(i);
    pieces.push_back(piece);
  }
  pieces.push_back(fixtures::paraboloidPiece(Vec2(-1, -1), Vec2(1.5, -1), Vec2(-1, 1.5)));
  pieces.back().triangle = 12;
  return pieces;
}

TEST(Accel, BezierPiecesAgreeWithTheDirectIntersector) {
  const FlushToZeroScope flushToZero;
  const std::vector<BezierTriangle> pieces = scatteredPieces();
  Accel accel(Accel::Options{false, true});
  const uint32_t id = accel.addBezierTriangles(pieces);
  accel.commit();
  EXPECT_EQ(accel.geometryBytes(), pieces.size() * sizeof(BezierTriangle));
  Pcg32 rng(37);
  std::vector<BezierHit> direct;
  std::vector<RayHit> hits;
  int hitCount = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target(3.0 * rng.nextDouble() - 0.5, 3.0 * rng.nextDouble() - 0.5,
                      3.0 * rng.nextDouble() - 0.5);
    const Vec3 d = uniformDirection(rng);
    const Ray ray{target - 4.0 * d, d, 0.0, 4.0 + 4.0 * rng.nextDouble()};
    // The direct answer: the nearest hit over every piece, and all of them.
    BezierHit best;
    uint32_t bestPiece = ~0u;
    size_t all = 0;
    for (uint32_t p = 0; p < pieces.size(); ++p) {
      BezierHit h;
      if (intersectBezierTriangle(pieces[p], ray.origin, ray.direction, ray.tnear, ray.tfar, h) &&
          h.t < best.t)
        best = h, bestPiece = p;
      direct.clear();
      all += intersectBezierTriangleAll(pieces[p], ray.origin, ray.direction, ray.tnear, ray.tfar,
                                        direct);
    }
    const RayHit hit = accel.intersect(ray);
    ASSERT_EQ(hit.valid(), bestPiece != ~0u) << i;
    EXPECT_EQ(accel.occluded(ray), bestPiece != ~0u) << i;
    hits.clear();
    accel.allHits(ray, hits);
    EXPECT_EQ(hits.size(), all) << i;
    if (!hit.valid()) continue;
    ++hitCount;
    EXPECT_EQ(hit.geometry, id);
    EXPECT_EQ(hit.primitive, bestPiece);
    EXPECT_EQ(hit.t, best.t);
    EXPECT_EQ(hit.u, best.u);
    EXPECT_EQ(hit.v, best.v);
    const Vec3 n = pieces[bestPiece].normal(best.u, best.v);
    EXPECT_NEAR((hit.geometricNormal - n).norm(), 0.0, 1e-15);
    EXPECT_NEAR(hit.geometricNormal.norm(), 1.0, 1e-12);
    for (const RayHit& h : hits) {
      EXPECT_EQ(h.geometry, id);
      EXPECT_NEAR(
          (pieces[h.primitive].position(h.u, h.v) - (ray.origin + h.t * ray.direction)).norm(), 0.0,
          1e-9);
    }
    // Just short of the nearest hit, nothing.
    EXPECT_FALSE(accel.occluded({ray.origin, ray.direction, 0.0, best.t * (1 - 1e-7)})) << i;
  }
  EXPECT_GT(hitCount, 2000);
}

// A rendering structure traces the pieces' sub-patches: the same nearest hits, to 1e-9, each
// reported as its piece's, and the same occlusion.
TEST(Accel, BezierSubPatchesAgreeWithTheDirectIntersector) {
  const FlushToZeroScope flushToZero;
  const std::vector<BezierTriangle> pieces = scatteredPieces();
  Accel accel;
  const uint32_t id = accel.addBezierTriangles(pieces);
  accel.commit();
  EXPECT_EQ(accel.geometryBytes(), pieces.size() * sizeof(BezierTriangle) +
                                       bezierSubPatches(pieces).size() * sizeof(BezierSubPatch));
  Pcg32 rng(53);
  int hitCount = 0, compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target(3.0 * rng.nextDouble() - 0.5, 3.0 * rng.nextDouble() - 0.5,
                      3.0 * rng.nextDouble() - 0.5);
    const Vec3 d = uniformDirection(rng);
    const Ray ray{target - 4.0 * d, d, 0.0, 4.0 + 4.0 * rng.nextDouble()};
    BezierHit best;
    uint32_t bestPiece = ~0u;
    for (uint32_t p = 0; p < pieces.size(); ++p) {
      BezierHit h;
      if (intersectBezierTriangle(pieces[p], ray.origin, ray.direction, ray.tnear, ray.tfar, h) &&
          h.t < best.t)
        best = h, bestPiece = p;
    }
    const RayHit hit = accel.intersect(ray);
    if (hit.valid()) {
      ++hitCount;
      EXPECT_EQ(hit.geometry, id);
      const BezierTriangle& piece = pieces[hit.primitive];
      EXPECT_NEAR((piece.position(hit.u, hit.v) - (ray.origin + hit.t * ray.direction)).norm(), 0.0,
                  1e-9 * (1.0 + hit.t));
      EXPECT_NEAR((hit.geometricNormal - piece.normal(hit.u, hit.v)).norm(), 0.0, 1e-12);
    }
    EXPECT_EQ(accel.occluded(ray), hit.valid()) << i;
    if (hit.valid() != (bestPiece != ~0u)) {
      // Only a ray within a hair of a double root may see it one way and not the other.
      const RayHit& h = hit.valid() ? hit : RayHit{};
      const Vec3 n = hit.valid() ? h.geometricNormal : pieces[bestPiece].normal(best.u, best.v);
      EXPECT_LT(std::abs(n.dot(d)), 1e-4) << i;
      continue;
    }
    if (!hit.valid()) continue;
    ++compared;
    EXPECT_NEAR(hit.t, best.t, 1e-9 * (1.0 + best.t)) << i;
    // Where two pieces' hits tie (a ray through their shared edge), either is the nearest.
    if (hit.primitive == bestPiece) {
      EXPECT_NEAR(hit.u, best.u, 1e-7) << i;
      EXPECT_NEAR(hit.v, best.v, 1e-7) << i;
    }
  }
  EXPECT_GT(compared, 2000);
  EXPECT_GE(hitCount, compared);
}

// A ray spawned from a hit names it (Ray::from*): the regions that hold the hit and prove the
// ray meets them at most once skip it, and nothing else changes. Rays leave random points of the
// pieces, offset as RenderScene::spawnRay does; their hits farther than a hair are every piece's
// nearest, their own piece's second meeting included, and with the origin named, fewer rays come
// back to where they started.
TEST(Accel, RaysLeavingAPieceSkipOnlyTheirOrigin) {
  const FlushToZeroScope flushToZero;
  const std::vector<BezierTriangle> pieces = scatteredPieces();
  Accel accel;
  const uint32_t id = accel.addBezierTriangles(pieces);
  accel.commit();
  Pcg32 rng(83);
  constexpr double kHair = 1e-6;
  int ownPieceAgain = 0, farHits = 0, selfHitsNamed = 0, selfHitsUnnamed = 0;
  for (int i = 0; i < 20000; ++i) {
    const uint32_t p = uint32_t(rng.nextDouble() * double(pieces.size() - 1));
    double u = rng.nextDouble(), v = rng.nextDouble();
    if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
    const Vec3 point = pieces[p].position(u, v), n = pieces[p].normal(u, v);
    const Vec3 d = uniformDirection(rng);
    Ray ray{point + (d.dot(n) >= 0.0 ? 1e-12 : -1e-12) * n, d, 0.0, 4.0};
    const RayHit unnamed = accel.intersect(ray);
    ray.fromGeometry = id;
    ray.fromPrimitive = p;
    ray.fromUV = Vec2(u, v);
    const RayHit named = accel.intersect(ray);
    EXPECT_EQ(accel.occluded(ray), named.valid()) << i;
    // The direct answer beyond a hair: every root of every piece.
    BezierHit best;
    uint32_t bestPiece = ~0u;
    std::vector<BezierHit> all;
    for (uint32_t q = 0; q < pieces.size(); ++q) {
      all.clear();
      intersectBezierTriangleAll(pieces[q], ray.origin, ray.direction, kHair, ray.tfar, all);
      for (const BezierHit& h : all)
        if (h.t < best.t) best = h, bestPiece = q;
    }
    selfHitsNamed += named.valid() && named.t <= kHair;
    selfHitsUnnamed += unnamed.valid() && unnamed.t <= kHair;
    if (named.valid() && named.t <= kHair) continue;
    ASSERT_EQ(named.valid(), bestPiece != ~0u) << i;
    if (!named.valid()) continue;
    ++farHits;
    ownPieceAgain += bestPiece == p;
    EXPECT_NEAR(named.t, best.t, 1e-9 * (1.0 + best.t)) << i;
    if (unnamed.valid() && unnamed.t > kHair) {
      EXPECT_EQ(named.t, unnamed.t) << i;
    }
  }
  EXPECT_GT(farHits, 2000);
  EXPECT_GT(ownPieceAgain, 50);
  EXPECT_LE(selfHitsNamed, selfHitsUnnamed);
}

// A rendering structure traces the flat pieces (a triangle, linearly parametrised) as native
// triangles: each hit still reports the piece, its (u, v) and its normal, in double precision,
// and a nearer curved piece still wins.
TEST(Accel, FlatBezierPiecesAreTracedAsTheirTriangles) {
  const FlushToZeroScope flushToZero;
  std::vector<BezierTriangle> pieces = scatteredPieces();
  Pcg32 rng(71);
  const size_t curved = pieces.size();
  for (int i = 0; i < 12; ++i) {
    const Vec3 base(2.0 * rng.nextDouble(), 2.0 * rng.nextDouble(), 2.0 * rng.nextDouble());
    BezierTriangle piece =
        fixtures::flatPiece(base, base + Vec3(0.6, 0.2, -0.3), base + Vec3(-0.1, 0.5, 0.4));
    piece.orientation = i % 2 ? 1.0 : -1.0;
    piece.triangle = uint32_t(curved + size_t(i));
    pieces.push_back(piece);
  }
  for (size_t p = 0; p < pieces.size(); ++p) EXPECT_EQ(pieces[p].isAffine(1e-12), p >= curved);
  Accel accel;
  const uint32_t id = accel.addBezierTriangles(pieces);
  accel.commit();
  int flatHits = 0, curvedHits = 0;
  std::vector<Ray> rays;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 target(3.0 * rng.nextDouble() - 0.5, 3.0 * rng.nextDouble() - 0.5,
                      3.0 * rng.nextDouble() - 0.5);
    const Vec3 d = uniformDirection(rng);
    const Ray ray{target - 4.0 * d, d, 0.0, 4.0 + 4.0 * rng.nextDouble()};
    rays.push_back(ray);
    BezierHit best;
    uint32_t bestPiece = ~0u;
    for (uint32_t p = 0; p < pieces.size(); ++p) {
      BezierHit h;
      if (intersectBezierTriangle(pieces[p], ray.origin, ray.direction, ray.tnear, ray.tfar, h) &&
          h.t < best.t)
        best = h, bestPiece = p;
    }
    const RayHit hit = accel.intersect(ray);
    // A ray within float round-off of a flat piece's edge may see it one way and not the other.
    if (hit.valid() != (bestPiece != ~0u) ||
        (hit.valid() && hit.primitive != bestPiece && std::abs(hit.t - best.t) < 1e-5)) {
      const double u = hit.valid() ? hit.u : best.u, v = hit.valid() ? hit.v : best.v;
      EXPECT_LT(std::min({u, v, 1.0 - u - v}), 1e-5) << i;
      continue;
    }
    EXPECT_EQ(accel.occluded(ray), hit.valid()) << i;
    if (!hit.valid()) continue;
    EXPECT_EQ(hit.geometry, id);
    ASSERT_EQ(hit.primitive, bestPiece) << i;
    (bestPiece >= curved ? flatHits : curvedHits)++;
    // In double precision again: as close as the direct intersector's Newton gets.
    EXPECT_NEAR(hit.t, best.t, 1e-9 * (1.0 + best.t)) << i;
    EXPECT_NEAR(hit.u, best.u, 1e-9) << i;
    EXPECT_NEAR(hit.v, best.v, 1e-9) << i;
    EXPECT_NEAR((hit.geometricNormal - pieces[bestPiece].normal(best.u, best.v)).norm(), 0.0,
                1e-12);
    // The hit's point is the piece's at its (u, v), flat pieces traced as triangles included.
    EXPECT_NEAR((hit.point - pieces[bestPiece].position(hit.u, hit.v)).norm(), 0.0, 1e-12) << i;
  }
  EXPECT_GT(flatHits, 1000);
  EXPECT_GT(curvedHits, 1000);
  // Traced in packets (the flat pieces through Embree's packet of triangles): the same hits.
  std::vector<RayHit> packed(rays.size());
  accel.intersect(rays, packed);
  for (size_t i = 0; i < rays.size(); ++i) {
    const RayHit one = accel.intersect(rays[i]);
    ASSERT_EQ(packed[i].primitive, one.primitive) << i;
    if (!one.valid()) continue;
    EXPECT_EQ(packed[i].t, one.t) << i;
    EXPECT_EQ(packed[i].u, one.u) << i;
    EXPECT_EQ(packed[i].v, one.v) << i;
    EXPECT_EQ(packed[i].point, one.point) << i;
  }
}

// isAffine holds at any scale and fails for a control point off the linear one by more than the
// tolerance.
TEST(BezierTriangle, AffineIsScaleInvariantAndStrict) {
  for (double scale : {1e-6, 1.0, 1e6}) {
    BezierTriangle piece =
        fixtures::flatPiece(scale * Vec3(1, 2, 3), scale * Vec3(2, 2, 3.5), scale * Vec3(1, 3, 2));
    EXPECT_TRUE(piece.isAffine(1e-12)) << scale;
    piece.at(2, 1, 1) += scale * Vec3(0, 0, 1e-9);
    EXPECT_FALSE(piece.isAffine(1e-12)) << scale;
    EXPECT_TRUE(piece.isAffine(1e-8)) << scale;
  }
}

TEST(Accel, BezierPieceOrientationSetsTheNormal) {
  BezierTriangle piece = fixtures::flatPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0));
  std::vector<BezierTriangle> up{piece};
  piece.orientation = -1.0;
  std::vector<BezierTriangle> down{piece};
  for (const auto* pieces : {&up, &down}) {
    Accel accel;
    accel.addBezierTriangles(*pieces);
    accel.commit();
    const RayHit hit = accel.intersect({Vec3(0.25, 0.25, 1), Vec3(0, 0, -1)});
    ASSERT_TRUE(hit.valid());
    EXPECT_NEAR(hit.t, 1.0, 1e-12);
    EXPECT_NEAR(hit.u, 0.25, 1e-12);
    EXPECT_NEAR(hit.v, 0.25, 1e-12);
    EXPECT_EQ(hit.geometricNormal, Vec3(0, 0, pieces->front().orientation));
  }
}

TEST(Accel, BadBezierPiecesAreAnError) {
  Accel accel;
  std::vector<BezierTriangle> none;
  EXPECT_THROW(accel.addBezierTriangles(none), Error);
  for (const double bad : {std::nan(""), kInfinity, -kInfinity}) {
    std::vector<BezierTriangle> pieces{
        fixtures::flatPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)),
        fixtures::flatPiece(Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1))};
    pieces[1].b[4].y() = bad;
    try {
      accel.addBezierTriangles(pieces);
      ADD_FAILURE() << bad << " accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("Bézier piece 1: a control point is not finite"),
                std::string::npos)
          << e.what();
    }
  }
  // The pieces are scanned in parallel blocks: the error still names the first bad piece.
  std::vector<BezierTriangle> many(
      40000, fixtures::flatPiece(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0)));
  many[31000].b[2].x() = kInfinity;
  many[9001].b[7].z() = std::nan("");
  many[30000].b[0].y() = -kInfinity;
  try {
    accel.addBezierTriangles(many);
    ADD_FAILURE() << "accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Bézier piece 9001: a control point is not finite"),
              std::string::npos)
        << e.what();
  }
}

ModelGeometry bezierGeometry(const std::vector<BezierTriangle>& pieces) {
  ModelGeometry g;
  g.bezier = &pieces;
  g.patchBytes = pieces.size() * sizeof(BezierTriangle);
  return g;
}

TEST(CrackRate, ClosedSurfacesOfBezierPiecesAreWatertight) {
  CrackRateOptions options;
  options.lines = fixtures::samples(100000);
  for (const double bulge : {0.0, 0.6})
    for (const bool split : {false, true}) {
      const std::vector<BezierTriangle> pieces = fixtures::octahedronPieces(bulge, split);
      ASSERT_TRUE(edgesShared(pieces)) << bulge << " " << split;
      EXPECT_EQ(crackRate(bezierGeometry(pieces), options), 0.0) << bulge << " " << split;
    }
}

TEST(CrackRate, BezierSurfaceWithAHoleCracks) {
  std::vector<BezierTriangle> pieces = fixtures::octahedronPieces(0.6, true);
  pieces.erase(pieces.begin() + 5);
  ASSERT_FALSE(edgesShared(pieces));
  CrackRateOptions options;
  options.lines = 20000;
  EXPECT_GT(crackRate(bezierGeometry(pieces), options), 0.003);
}

// A Bezier model for the tests: the octahedron's pieces over its 8 faces.
class PiecesModel : public SurfaceModel {
 public:
  explicit PiecesModel(std::vector<BezierTriangle> pieces)
      : SurfaceModel(octahedronMesh()), pieces_(std::move(pieces)) {}
  std::string_view name() const override { return "test-bezier"; }
  SurfacePoint evaluate(size_t t, double u, double v) const override {
    return {pieces_[t].position(u, v), pieces_[t].normal(u, v)};
  }
  Representation representation() const override { return Representation::Bezier; }
  const std::vector<BezierTriangle>& bezierPieces() const override { return pieces_; }
  void patchRecord(size_t, PatchRecord&) const override {}

 private:
  static std::shared_ptr<const TriangleMesh> octahedronMesh() {
    auto mesh = std::make_shared<TriangleMesh>();
    mesh->positions = {Vec3(1, 0, 0),  Vec3(-1, 0, 0), Vec3(0, 1, 0),
                       Vec3(0, -1, 0), Vec3(0, 0, 1),  Vec3(0, 0, -1)};
    for (uint32_t sx : {0u, 1u})
      for (uint32_t sy : {2u, 3u})
        for (uint32_t sz : {4u, 5u}) mesh->triangles.push_back({sx, sy, sz});
    return mesh;
  }
  std::vector<BezierTriangle> pieces_;
};

TEST(CrackRate, BezierModelGeometry) {
  const PiecesModel model(fixtures::octahedronPieces(0.6, true));
  const ModelGeometry g = modelGeometry(model, Tessellation{});
  ASSERT_EQ(g.bezier, &model.bezierPieces());
  EXPECT_EQ(g.patches, nullptr);
  EXPECT_EQ(g.primitiveCount(), 32u);
  EXPECT_EQ(g.bytes(), 32 * sizeof(BezierTriangle));
  CrackRateOptions options;
  options.lines = 20000;
  EXPECT_EQ(crackRate(g, options), 0.0);
  const PiecesModel empty({});
  EXPECT_THROW(modelGeometry(empty, Tessellation{}), Error);
  std::vector<BezierTriangle> stray = fixtures::octahedronPieces(0.0, false);
  stray[3].triangle = 8;
  EXPECT_THROW(modelGeometry(PiecesModel(stray), Tessellation{}), Error);
}

TEST(RenderScene, BezierHitsLieOnThePiece) {
  auto model = std::make_shared<PiecesModel>(fixtures::octahedronPieces(0.6, true));
  auto bsdf = std::make_shared<Diffuse>(Color::Constant(0.5));
  RenderScene scene;
  EXPECT_THROW(scene.addModel(model, Tessellation{}, bsdf, Color::Constant(1.0), "lamp"), Error);
  const uint32_t id = scene.addModel(model, Tessellation{}, bsdf, std::nullopt, "bulge");
  scene.commit();
  EXPECT_EQ(scene.primitiveCount(), 32u);
  Pcg32 rng(41);
  int hits = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec3 d = uniformDirection(rng);
    const Ray ray{-4.0 * d + 0.8 * uniformDirection(rng), d};
    const auto si = scene.intersect(ray);
    if (!si) continue;
    ++hits;
    EXPECT_EQ(si->geometryId, id);
    ASSERT_LT(si->primitive, model->bezierPieces().size());
    EXPECT_NEAR((si->p - (ray.origin + si->t * ray.direction)).norm(), 0.0, 1e-9);
    EXPECT_NEAR(si->geometricNormal.norm(), 1.0, 1e-12);
    EXPECT_EQ(si->geometricNormal, si->shadingNormal);
    EXPECT_LT(si->geometricNormal.dot(ray.direction), 0.0);  // outward, seen from outside
    EXPECT_GT(si->offset, 0.0);
    EXPECT_EQ(si->liftedP, si->p);
    // Leaving outward finds nothing; leaving inward finds the far side.
    EXPECT_FALSE(scene.intersect(scene.spawnRay(*si, si->geometricNormal))) << i;
    const auto far = scene.intersect(scene.spawnRay(*si, -si->geometricNormal));
    ASSERT_TRUE(far) << i;
    EXPECT_GT(far->t, 1e-3);
  }
  EXPECT_GT(hits, 1000);
}

}  // namespace
}  // namespace quadtri
