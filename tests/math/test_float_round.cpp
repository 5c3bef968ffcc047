#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "quadtri/math/float_round.h"

namespace quadtri {
namespace {

using FloatLimits = std::numeric_limits<float>;

// The bit steps agree with std::nextafter bit for bit, at the zeros, the subnormals, the
// largest finite floats and the infinities, and on random floats of every exponent.
TEST(FloatRound, StepsAreNextafterBitForBit) {
  std::vector<float> cases = {0.0f,
                              -0.0f,
                              FloatLimits::denorm_min(),
                              -FloatLimits::denorm_min(),
                              FloatLimits::min(),
                              -FloatLimits::min(),
                              1.0f,
                              -1.0f,
                              FloatLimits::max(),
                              -FloatLimits::max(),
                              FloatLimits::infinity(),
                              -FloatLimits::infinity()};
  std::mt19937 rng(11);
  std::uniform_int_distribution<uint32_t> bits;
  while (cases.size() < 100000) {
    const float f = std::bit_cast<float>(bits(rng));
    if (!std::isnan(f)) cases.push_back(f);
  }
  for (const float f : cases) {
    const float below = floatBelow(f), above = floatAbove(f);
    EXPECT_EQ(std::bit_cast<uint32_t>(below),
              std::bit_cast<uint32_t>(std::nextafter(f, -FloatLimits::infinity())))
        << f;
    EXPECT_EQ(std::bit_cast<uint32_t>(above),
              std::bit_cast<uint32_t>(std::nextafter(f, FloatLimits::infinity())))
        << f;
  }
}

// floatDown and floatUp give the nearest float on their side of any double, exact floats kept.
TEST(FloatRound, RoundsToTheChosenSide) {
  std::mt19937_64 rng(5);
  std::uniform_int_distribution<uint64_t> bits;
  int rounded = 0;
  for (int i = 0; i < 100000; ++i) {
    const double x = std::bit_cast<double>(bits(rng));
    if (std::isnan(x)) continue;
    const float down = floatDown(x), up = floatUp(x);
    EXPECT_LE(double(down), x);
    EXPECT_GE(double(up), x);
    if (double(down) == x) {
      EXPECT_EQ(down, up);
    } else {
      ++rounded;
      EXPECT_EQ(std::nextafter(down, FloatLimits::infinity()), up) << x;
    }
  }
  EXPECT_GT(rounded, 90000);
  EXPECT_EQ(floatDown(1.0), 1.0f);
  EXPECT_EQ(floatUp(-0.0), -0.0f);
  EXPECT_EQ(floatDown(1e300), FloatLimits::max());
  EXPECT_EQ(floatUp(1e300), FloatLimits::infinity());
  EXPECT_EQ(floatDown(-1e300), -FloatLimits::infinity());
  EXPECT_EQ(floatUp(1e-300), FloatLimits::denorm_min());
  EXPECT_EQ(floatDown(1e-300), 0.0f);
}

}  // namespace
}  // namespace quadtri
