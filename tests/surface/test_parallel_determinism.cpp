// Conversion runs in parallel over triangles and edges: with 1 and with 2 threads every model
// must give the same patch records, bit for bit. So must tessellation, which numbers the
// lattice's points as a walk over the triangles in order would and evaluates them in parallel.
#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "quadtri/mesh/shapes.h"
#include "quadtri/surface/model.h"
#include "quadtri/surface/quadric_patch.h"
#include "quadtri/surface/tessellate.h"

namespace quadtri {
namespace {

// Every number a model records: its patches' JSON, its patch evaluations at a few points and,
// for implicit models, every field of every render primitive (bridges included).
struct Record {
  std::string json;
  std::vector<double> numbers;
  std::vector<int64_t> integers;
};

void add(Record& r, const Vec3& v) {
  r.numbers.insert(r.numbers.end(), {v.x(), v.y(), v.z()});
}

Record record(const SurfaceModel& model) {
  Record r;
  for (size_t t = 0; t < model.patchCount(); ++t) {
    r.json += model.patchJson(t).dump();
    for (const auto& [u, v] : {std::pair{1.0 / 3, 1.0 / 3}, std::pair{0.5, 0.25}}) {
      const SurfacePoint p = model.evaluate(t, u, v);
      add(r, p.position);
      add(r, p.normal);
    }
    r.integers.push_back(model.fellBack(t));
  }
  for (const QuadricPatch& p : model.renderPatches()) {
    r.numbers.insert(r.numbers.end(), p.q.begin(), p.q.end());
    for (const Vec4& plane : p.planes)
      r.numbers.insert(r.numbers.end(), plane.data(), plane.data() + 4);
    add(r, p.bounds.lo);
    add(r, p.bounds.hi);
    r.numbers.push_back(p.orientation);
    r.numbers.insert(r.numbers.end(), p.base.data(), p.base.data() + 4);
    r.integers.insert(r.integers.end(),
                      {p.planeCount, p.joins[0], p.joins[1], p.joinPlanes[0], p.joinPlanes[1]});
  }
  return r;
}

Record convertWith(int threads, const std::string& model,
                   const std::shared_ptr<const TriangleMesh>& mesh) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return record(*makeModel(model, mesh));
}

TEST(ParallelConversion, OneAndTwoThreadsGiveBitwiseEqualPatches) {
  // A torus (generic data) and an icosphere (data from a quadric), large enough that every
  // parallel loop splits.
  for (const char* spec : {"torus:1,0.35,96,48", "icosphere:4"}) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    for (const std::string& model : modelNames()) {
      SCOPED_TRACE(std::string(spec) + " " + model);
      const Record one = convertWith(1, model, mesh);
      const Record two = convertWith(2, model, mesh);
      EXPECT_EQ(one.json, two.json);
      EXPECT_EQ(one.integers, two.integers);
      ASSERT_EQ(one.numbers.size(), two.numbers.size());
      // Bitwise: memcmp, so that a NaN compares equal to itself and -0 differs from +0.
      EXPECT_EQ(
          std::memcmp(one.numbers.data(), two.numbers.data(), one.numbers.size() * sizeof(double)),
          0);
    }
  }
}

TriangleMesh tessellateWith(int threads, const SurfaceModel& model, const Tessellation& t) {
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
  return tessellate(model, t);
}

bool sameBits(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(Vec3)) == 0;
}

TEST(ParallelTessellation, OneAndTwoThreadsGiveTheSameLattice) {
  // The cylinder splits its normals at the rims (crease points get normals of their own), the
  // torus does not; at levels 1 and 3 both are large enough that the loops split, and the
  // thesis grid (whose last row of points all lie at corner 2) runs on a small cylinder.
  const std::vector<std::pair<const char*, Tessellation>> cases = {
      {"cylinder:64,32", Tessellation{Tessellation::Kind::Lattice, 1}},
      {"cylinder:64,32", Tessellation{Tessellation::Kind::Lattice, 3}},
      {"torus:1,0.35,64,32", Tessellation{Tessellation::Kind::Lattice, 3}},
      {"cylinder:8,2", Tessellation::thesis()}};
  for (const auto& [spec, level] : cases) {
    const auto mesh = std::make_shared<const TriangleMesh>(parseBuiltinSpec(spec)->mesh);
    for (const std::string& name : modelNames()) {
      SCOPED_TRACE(std::string(spec) + " " + name + " level " + std::to_string(level.level));
      const auto model = makeModel(name, mesh);
      const TriangleMesh one = tessellateWith(1, *model, level);
      const TriangleMesh two = tessellateWith(2, *model, level);
      EXPECT_EQ(one.triangles, two.triangles);
      EXPECT_EQ(one.normalIndices, two.normalIndices);
      EXPECT_TRUE(sameBits(one.positions, two.positions));
      EXPECT_TRUE(sameBits(one.normals, two.normals));
      if (model->sharesEdges() && model->representation() != Representation::InputTriangles &&
          std::string(spec).starts_with("cylinder")) {
        EXPECT_GT(one.normals.size(), one.positions.size());  // the rims' own normals
      }
    }
  }
}

}  // namespace
}  // namespace quadtri
