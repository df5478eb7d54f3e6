#pragma once
// Internal: the one stream splitter of octoreach (SplitMix64 finaliser). Item i of a batch gets the
// random stream mix64(seed, i), so results depend on the seed and the item, never on the thread count.
#include <cstdint>
#include <optional>
#include <random>

namespace octoreach::detail {

/// \brief A well mixed 64-bit value of (seed, i): the seed of item i's random stream.
inline std::uint64_t mix64(std::uint64_t seed, std::uint64_t i) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (i + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

/// \brief The SplitMix64 finaliser alone: a bijective mix of one 64-bit value (hashing keys).
inline std::uint64_t mix_bits(std::uint64_t x) {
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// \brief std::mt19937_64 seeded with `seed`, its first kDraws numbers made without the engine's 312-word state:
/// seeding it and making its first number walks all 312 words twice, where the first few numbers need only the
/// seed's words up to 155 + kDraws and the twist of the first kDraws. For a stream per item (a sampled pose's few
/// draws) that is most of the item's cost. Past kDraws it runs the engine itself. A UniformRandomBitGenerator.
class Mt64Prefix {
 public:
  static constexpr int kDraws = 8;
  using result_type = std::uint64_t;
  static constexpr result_type min() { return 0; }
  static constexpr result_type max() { return ~result_type(0); }
  explicit Mt64Prefix(std::uint64_t seed) : seed_(seed) {
    std::uint64_t x = seed;  // the seeding recurrence of std::mt19937_64, word i
    lo_[0] = x;
    for (int i = 1; i < kShift + kDraws; ++i) {
      x = 6364136223846793005ULL * (x ^ (x >> 62)) + std::uint64_t(i);
      if (i <= kDraws) lo_[i] = x;
      if (i >= kShift) hi_[i - kShift] = x;
    }
  }
  result_type operator()() {
    if (n_ >= kDraws) {
      if (n_++ == kDraws) rest_.emplace(seed_).discard(kDraws);
      return (*rest_)();
    }
    // the twist of word n (its upper bit, the next word's lower 31, the word 156 on), then the tempering
    const std::uint64_t y = (lo_[n_] & 0xFFFFFFFF80000000ULL) | (lo_[n_ + 1] & 0x7FFFFFFFULL);
    std::uint64_t z = hi_[n_] ^ (y >> 1) ^ ((y & 1) ? 0xB5026F5AA96619E9ULL : 0);
    ++n_;
    z ^= (z >> 29) & 0x5555555555555555ULL;
    z ^= (z << 17) & 0x71D67FFFEDA60000ULL;
    z ^= (z << 37) & 0xFFF7EEE000000000ULL;
    return z ^ (z >> 43);
  }

 private:
  static constexpr int kShift = 156;  // the twist's middle word
  std::uint64_t seed_, lo_[kDraws + 1], hi_[kDraws];
  int n_ = 0;
  std::optional<std::mt19937_64> rest_;  // past kDraws: the engine itself (seeded then)
};

}  // namespace octoreach::detail
