// The kinematics' sine and cosine (cpp/src/common/sin_cos.hpp) against the C library's.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "common/sin_cos.hpp"

using octoreach::detail::sin_cos;

namespace {

// Units in the last place between a and b (b the C library's value), 0 when equal.
double ulps(double a, double b) {
  if (a == b) return 0.0;
  const double scale = std::max(std::abs(b), std::numeric_limits<double>::min());
  return std::abs(a - b) / (std::nextafter(scale, 2 * scale + 1) - scale);
}

}  // namespace

TEST(SinCos, WithinTwoUlpOfTheCLibraryOnJointAngles) {
  std::mt19937_64 rng(7);
  double worst = 0.0;
  for (double range : {1e-6, 1.0, 3.2, 7.0, 100.0, 9.9e4}) {
    std::uniform_real_distribution<double> u(-range, range);
    for (int i = 0; i < 200000; ++i) {
      const double x = u(rng);
      double s, c;
      sin_cos(x, s, c);
      // Away from a zero of sin or cos, 2 ulp of the value; at a zero, the C library's own value is a rounding of
      // the exact one and the distance is measured in ulp of 1 (the reduction's error is absolute).
      const double es = std::abs(std::sin(x)) > 1e-3 ? ulps(s, std::sin(x)) : std::abs(s - std::sin(x)) / 2.2e-16;
      const double ec = std::abs(std::cos(x)) > 1e-3 ? ulps(c, std::cos(x)) : std::abs(c - std::cos(x)) / 2.2e-16;
      worst = std::max({worst, es, ec});
      ASSERT_LE(es, 2.0) << "sin " << x;
      ASSERT_LE(ec, 2.0) << "cos " << x;
    }
  }
  EXPECT_GT(worst, 0.0);  // not the C library itself
}

TEST(SinCos, ExactWhereTheCLibraryIs) {
  double s, c;
  sin_cos(0.0, s, c);
  EXPECT_EQ(s, 0.0);
  EXPECT_EQ(c, 1.0);
  sin_cos(-0.0, s, c);
  EXPECT_EQ(c, 1.0);
  for (double x : {1e5, -2e5, 1e300}) {  // past the reduction: the C library
    sin_cos(x, s, c);
    EXPECT_EQ(s, std::sin(x)) << x;
    EXPECT_EQ(c, std::cos(x)) << x;
  }
  sin_cos(std::numeric_limits<double>::infinity(), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
  sin_cos(std::numeric_limits<double>::quiet_NaN(), s, c);
  EXPECT_TRUE(std::isnan(s) && std::isnan(c));
}
