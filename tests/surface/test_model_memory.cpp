// What rendering and conversion charge against --max-memory per model (model_memory.h).
#include <gtest/gtest.h>

#include "quadtri/math/error.h"
#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/bezier_intersect.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/model_memory.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

// Every model has its own memory cost beside its factory: a model traced as it is (input
// triangles, quadric patches, Bézier pieces) costs the same to render at any tessellation
// level, a tessellated one grows with it, and an unknown name costs the dearest model's.
TEST(ModelMemory, EveryModelHasItsOwnCost) {
  const Tessellation coarse{Tessellation::Kind::Lattice, 2}, fine{Tessellation::Kind::Lattice, 16};
  uint64_t dearest = 0;
  for (const std::string& name : modelNames()) {
    SCOPED_TRACE(name);
    const Representation r =
        makeModel(name, std::make_shared<const TriangleMesh>(parseBuiltinSpec("icosahedron")->mesh))
            ->representation();
    const uint64_t a = modelBytesPerTriangle(name, coarse, ModelUse::Render);
    const uint64_t b = modelBytesPerTriangle(name, fine, ModelUse::Render);
    EXPECT_GT(a, 0u);
    if (r == Representation::Tessellated) {
      EXPECT_EQ(b, 64 * a);  // 256 lattice triangles against 4
    } else {
      EXPECT_EQ(a, b);
    }
    EXPECT_GT(modelBytesPerTriangle(name, fine, ModelUse::ConvertJson), 0u);
    dearest = std::max(dearest, b);
  }
  EXPECT_EQ(modelBytesPerTriangle("no-such-model", fine, ModelUse::Render), dearest);
}

// A quadric patch's record: a 16-byte header (bridge sides, plane count and the float sign),
// the ten coefficients, the box, six planes and the base plane, with no padding between them
// where Vec4 is 16-byte aligned (no AVX: 368 bytes; with AVX the planes start at 160).
TEST(ModelMemory, QuadricPatchRecordHasNoPadding) {
  const size_t head = 16 + 10 * 8 + 6 * 8;
  const size_t planesAt = (head + alignof(Vec4) - 1) / alignof(Vec4) * alignof(Vec4);
  EXPECT_EQ(sizeof(QuadricPatch), planesAt + (QuadricPatch::kMaxPlanes + 1) * sizeof(Vec4));
  if (alignof(Vec4) == 16) {
    EXPECT_EQ(sizeof(QuadricPatch), 368u);
  }
}

// An automatic tessellation is charged at level 1 before the mesh is loaded, and what the level
// it picks costs beyond that once it is known; a charge over the limit is refused with the
// level named, leaving the budget as it was.
TEST(ModelMemory, AutoTessellationIsChargedAtTheLevelItPicks) {
  const Tessellation automatic = Tessellation::adaptive();
  const Tessellation one{Tessellation::Kind::Lattice, 1}, five{Tessellation::Kind::Lattice, 5};
  for (const ModelUse use : {ModelUse::Render, ModelUse::ConvertMesh}) {
    EXPECT_EQ(modelBytesPerTriangle("pn", automatic, use), modelBytesPerTriangle("pn", one, use));
    MemoryBudget budget;
    setModelBytes(budget, "pn", automatic, use);
    chargeMemory(budget, modelBytes(budget, 1000), "mesh", "loading");
    const uint64_t before = budget.usedBytes;
    chargeResolvedTessellation(budget, "pn", automatic, five, use, 1000, "mesh");
    EXPECT_EQ(budget.usedBytes - before, 1000 * (modelBytesPerTriangle("pn", five, use) -
                                                 modelBytesPerTriangle("pn", one, use)));
    // Level 1, or a tessellation that was not automatic, costs nothing more.
    const uint64_t charged = budget.usedBytes;
    chargeResolvedTessellation(budget, "pn", automatic, one, use, 1000, "mesh");
    chargeResolvedTessellation(budget, "pn", five, five, use, 1000, "mesh");
    EXPECT_EQ(budget.usedBytes, charged);
    budget.maxBytes = charged + 10;
    try {
      chargeResolvedTessellation(budget, "pn", automatic, five, use, 1000, "cow.off");
      ADD_FAILURE() << "accepted";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find("cow.off: tessellating its 1000 triangles at level 5"),
                std::string::npos)
          << e.what();
    }
    EXPECT_EQ(budget.usedBytes, charged);
  }
}

// quadric-g1's regions are charged as many as defaultSubPatchBudget gives its three pieces per
// triangle, so a fine mesh is no longer charged regions it will not get, but never fewer than
// one per piece, which a mesh past the cap still gets; no other model has a capped part, and
// nothing is capped but in rendering.
TEST(ModelMemory, G1RegionsAreChargedAsTheirBudgetCapsThem) {
  const Tessellation tess;
  const CappedModelBytes g1 = modelCappedBytes("quadric-g1", ModelUse::Render);
  ASSERT_GT(g1.perTriangle, 0u);
  const double perRegion = double(g1.cap) / double(defaultSubPatchBudget(size_t(1) << 40));
  for (const uint64_t triangles : {uint64_t(20), uint64_t(1000), uint64_t(81920), uint64_t(87381),
                                   uint64_t(174762), uint64_t(1000000)}) {
    SCOPED_TRACE(triangles);
    MemoryBudget budget;
    setModelBytes(budget, "quadric-g1", tess, ModelUse::Render);
    // What it gets: the rest of the model per triangle, and max(one region per piece, the
    // budget's regions).
    const double rest = double(budget.bytesPerTriangle) - 3.0 * perRegion;
    const double regions =
        std::max(3.0 * double(triangles), double(defaultSubPatchBudget(3 * triangles)));
    const double gets = double(triangles) * rest + regions * perRegion;
    const double charged = double(modelBytes(budget, triangles));
    // All of that (a small mesh gets the budget's floor of 65,536 regions), and at most the
    // cap's regions more.
    EXPECT_GE(charged, gets - 1e-9 * gets - 1.0);
    EXPECT_LE(charged, gets + double(g1.cap) + 1.0);
  }
  // Past the cap the regions grow only as the pieces: a million more triangles cost three
  // regions each beside the rest, not the 24 of a small mesh.
  MemoryBudget budget;
  setModelBytes(budget, "quadric-g1", tess, ModelUse::Render);
  EXPECT_EQ(modelBytes(budget, 2000000) - modelBytes(budget, 1000000),
            1000000 * budget.bytesPerTriangle);
  for (const std::string& name : modelNames()) {
    SCOPED_TRACE(name);
    EXPECT_EQ(modelCappedBytes(name, ModelUse::ConvertJson).cap, 0u);
    EXPECT_EQ(modelCappedBytes(name, ModelUse::ConvertMesh).cap, 0u);
    // A streamed surface holds one block at most: it stops growing at its cap.
    const CappedModelBytes block = modelCappedBytes(name, ModelUse::ConvertMeshStreamed, tess);
    const uint64_t streamed = modelBytesPerTriangle(name, tess, ModelUse::ConvertMeshStreamed);
    const bool input = streamed == modelBytesPerTriangle(name, tess, ModelUse::ConvertMesh);
    EXPECT_EQ(block.cap == 0, input);
    if (!input) {
      const MemoryBudget charged{0, streamed, block.perTriangle, block.cap};
      EXPECT_GT(block.perTriangle, 0u);
      EXPECT_EQ(modelBytes(charged, 2000000) - modelBytes(charged, 1000000), 1000000 * streamed);
    }
    if (name != "quadric-g1") {
      EXPECT_EQ(modelCappedBytes(name, ModelUse::Render).cap, 0u);
    }
  }
  EXPECT_EQ(modelCappedBytes("no-such-model", ModelUse::Render).cap, g1.cap);
  // setModelBytes replaces a budget's model, and with `dearest` keeps the larger of each part.
  setModelBytes(budget, "phong", tess, ModelUse::Render);
  EXPECT_EQ(budget.cappedBytes, 0u);
  setModelBytes(budget, "quadric-g1", tess, ModelUse::Render, /*dearest=*/true);
  EXPECT_EQ(budget.cappedBytes, g1.cap);
  EXPECT_EQ(budget.bytesPerTriangle,
            std::max(modelBytesPerTriangle("phong", tess, ModelUse::Render),
                     modelBytesPerTriangle("quadric-g1", tess, ModelUse::Render)));
}

}  // namespace
}  // namespace quadtri
