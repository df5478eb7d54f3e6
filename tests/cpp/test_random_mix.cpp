// The seeds' helpers (cpp/src/common/random_mix.hpp): Mt64Prefix against std::mt19937_64.
#include <gtest/gtest.h>

#include <random>

#include "common/random_mix.hpp"

using octoreach::detail::Mt64Prefix;

TEST(Mt64Prefix, MakesTheFirstNumbersOfMt19937_64) {
  std::mt19937_64 seeds(11);
  for (int k = 0; k < 2000; ++k) {
    // edge seeds too: 0, all ones, the default seed, and seeds whose top bits feed the recurrence's shift
    const std::uint64_t seed = k == 0 ? 0 : k == 1 ? ~std::uint64_t(0) : k == 2 ? 5489u : k == 3 ? (std::uint64_t(3) << 62) : seeds();
    std::mt19937_64 ref(seed);
    Mt64Prefix fast(seed);
    for (int i = 0; i < Mt64Prefix::kDraws; ++i) ASSERT_EQ(fast(), ref()) << "seed " << seed << ", draw " << i;
  }
}

TEST(Mt64Prefix, GivesTheSameUniformDoubles) {
  for (std::uint64_t seed : {1ULL, 42ULL, 0x9E3779B97F4A7C15ULL}) {
    std::mt19937_64 ref(seed);
    Mt64Prefix fast(seed);
    std::uniform_real_distribution<double> u(0.0, 1.0), v(0.0, 1.0);
    for (int i = 0; i < Mt64Prefix::kDraws; ++i) EXPECT_EQ(u(fast), v(ref));
  }
}

TEST(Mt64Prefix, GoesOnAsTheEnginePastItsPrefix) {
  std::mt19937_64 ref(3);
  Mt64Prefix fast(3);
  for (int i = 0; i < 3 * Mt64Prefix::kDraws; ++i) EXPECT_EQ(fast(), ref()) << "draw " << i;
}
