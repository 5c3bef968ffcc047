// PatchRecord, the patch data that the JSON and binary outputs are written from: it holds what a
// JSON object would (members sorted by key, replaced when set again), converts both ways, and
// dumps the bytes nlohmann::json's dump() writes for the same value.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>

#include "quadtri/math/error.h"
#include "quadtri/surface/patch_record.h"

namespace quadtri {
namespace {

using Ref = PatchRecord::Ref;
constexpr Ref kRoot = PatchRecord::kRoot;

TEST(PatchRecord, MembersAreSortedAndReplacedAsInAJsonObject) {
  PatchRecord r;
  r.set(kRoot, "zeta", 1.5);
  r.setInt(kRoot, "alpha", -3);
  r.setBool(kRoot, "mid", true);
  const Ref list = r.setArray(kRoot, "beta");
  r.push(list, Vec3(1, 2, 3));
  r.pushInt(list, 7);
  r.set(kRoot, "zeta", 2.5);  // replaces, keeps one member
  EXPECT_EQ(r.size(kRoot), 4u);
  std::vector<std::string> keys;
  for (Ref at = r.first(kRoot); at != PatchRecord::kNone; at = r.next(at))
    keys.emplace_back(r.key(at));
  EXPECT_EQ(keys, (std::vector<std::string>{"alpha", "beta", "mid", "zeta"}));
  EXPECT_EQ(r.number(r.find(kRoot, "zeta")), 2.5);
  EXPECT_EQ(r.integer(r.find(kRoot, "alpha")), -3);
  EXPECT_EQ(r.find(kRoot, "missing"), PatchRecord::kNone);
  const nlohmann::json want = {
      {"alpha", -3}, {"beta", {{1.0, 2.0, 3.0}, 7}}, {"mid", true}, {"zeta", 2.5}};
  EXPECT_EQ(r.toJson(), want);
  r.clear();
  EXPECT_EQ(r.size(kRoot), 0u);
  EXPECT_EQ(r.toJson(), nlohmann::json::object());
}

// A random JSON value of the kinds patch records hold, `depth` levels deep at most.
nlohmann::json randomValue(std::mt19937& rng, int depth) {
  const auto pick = [&](int n) { return int(rng() % unsigned(n)); };
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  switch (depth > 0 ? pick(8) : pick(5)) {
    case 0:
      return pick(2) == 0;
    case 1:
      return int64_t(rng()) - int64_t(1) * (int64_t(1) << 31);
    case 2: {
      // Doubles across the exponent range, integral ones and the non-finite ones dump as null.
      const double specials[] = {0.0,
                                 -0.0,
                                 1.0,
                                 1e15,
                                 1e16,
                                 1e-5,
                                 1e-4,
                                 123456789.0,
                                 std::numeric_limits<double>::quiet_NaN(),
                                 std::numeric_limits<double>::infinity(),
                                 std::numeric_limits<double>::denorm_min(),
                                 std::numeric_limits<double>::max()};
      if (pick(3) == 0) return specials[pick(12)];
      return uniform(rng) * std::pow(10.0, pick(600) - 300);
    }
    case 3:
      return uniform(rng);
    case 4:
      return nullptr;
    case 5:
    case 6: {
      nlohmann::json a = nlohmann::json::array();
      for (int i = 0, n = pick(4); i < n; ++i) a.push_back(randomValue(rng, depth - 1));
      return a;
    }
    default: {
      nlohmann::json o = nlohmann::json::object();
      const char* const keys[] = {
          "a", "b01", "quadric", "Z", "key with \"quote\"", "tab\t", "\xc3\xa9t\xc3\xa9", "planes"};
      for (int i = 0, n = pick(4); i < n; ++i) o[keys[pick(8)]] = randomValue(rng, depth - 1);
      return o;
    }
  }
}

TEST(PatchRecord, DumpIsTheJsonDumpOfTheSameValue) {
  std::mt19937 rng(11);
  for (int trial = 0; trial < 2000; ++trial) {
    nlohmann::json j = nlohmann::json::object();
    for (const char* key : {"k0", "k1", "k2", "k3"}) j[key] = randomValue(rng, 3);
    const PatchRecord r = PatchRecord::fromJson(j);
    std::string text;
    r.dump(text);
    ASSERT_EQ(text, j.dump()) << "trial " << trial;
    ASSERT_EQ(r.toJson().dump(), j.dump()) << "trial " << trial;
  }
}

TEST(PatchRecord, FromJsonLeavesStringsOutAndRefusesWhatIsNotAnObject) {
  const PatchRecord r =
      PatchRecord::fromJson({{"name", "skipped"}, {"x", 1.0}, {"list", {1.0, "text"}}});
  EXPECT_EQ(r.toJson(), (nlohmann::json{{"x", 1.0}, {"list", {1.0, nullptr}}}));
  try {
    PatchRecord::fromJson(nlohmann::json::array());
    FAIL() << "an array was taken as a record";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("must be an object, not array"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace quadtri
