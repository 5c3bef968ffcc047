#include <gtest/gtest.h>

#include <numeric>
#include <vector>

#include "quadtri/math/fixed_vector.h"
#include "quadtri/math/vec.h"

namespace quadtri {
namespace {

TEST(FixedVector, HoldsWhatAStdVectorHoldsUpToItsCapacity) {
  FixedVector<int, 5> v;
  std::vector<int> reference;
  EXPECT_TRUE(v.empty());
  EXPECT_EQ(v.capacity(), 5u);
  for (int i = 0; i < 5; ++i) {
    EXPECT_FALSE(v.full());
    v.push_back(10 * i + 3);
    reference.push_back(10 * i + 3);
    ASSERT_EQ(v.size(), reference.size());
    EXPECT_EQ(std::vector<int>(v.begin(), v.end()), reference);
    EXPECT_EQ(v.back(), reference.back());
  }
  EXPECT_TRUE(v.full());
  EXPECT_EQ(std::accumulate(v.begin(), v.end(), 0),
            std::accumulate(reference.begin(), reference.end(), 0));
  v.resize(2);
  EXPECT_EQ(std::vector<int>(v.begin(), v.end()), (std::vector<int>{3, 13}));
  v.resize(4);  // grown elements are value-initialised
  EXPECT_EQ(std::vector<int>(v.begin(), v.end()), (std::vector<int>{3, 13, 0, 0}));
  v.clear();
  EXPECT_TRUE(v.empty());
}

TEST(FixedVector, CopiesAreIndependentAndKeepEigenValues) {
  FixedVector<Vec4, 3> a{Vec4(1, 2, 3, 4), Vec4(-1, 0.5, 1e300, -0.0)};
  FixedVector<Vec4, 3> b = a;
  ASSERT_EQ(b.size(), 2u);
  EXPECT_EQ(b[0], Vec4(1, 2, 3, 4));
  EXPECT_EQ(b[1], Vec4(-1, 0.5, 1e300, -0.0));
  b[0].x() = 7;
  b.push_back(Vec4::Ones());
  EXPECT_EQ(a[0].x(), 1);
  EXPECT_EQ(a.size(), 2u);
  a = b;
  EXPECT_EQ(a.size(), 3u);
  EXPECT_EQ(a[0].x(), 7);
  EXPECT_EQ(a[2], Vec4::Ones());
  // Nested, as a convex cell's faces are.
  FixedVector<FixedVector<int8_t, 4>, 2> faces;
  faces.resize(2);
  faces[1].push_back(3);
  const auto copy = faces;
  EXPECT_TRUE(copy[0].empty());
  ASSERT_EQ(copy[1].size(), 1u);
  EXPECT_EQ(copy[1][0], 3);
  const std::vector<double> from = {1.5, 2.5};
  const FixedVector<double, 4> ranged(from.begin(), from.end());
  EXPECT_EQ(std::vector<double>(ranged.begin(), ranged.end()), from);
}

}  // namespace
}  // namespace quadtri
