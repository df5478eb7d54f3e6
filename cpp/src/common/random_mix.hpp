#pragma once
// Internal: the one stream splitter of octoreach (SplitMix64 finaliser). Item i of a batch gets the
// random stream mix64(seed, i), so results depend on the seed and the item, never on the thread count.
#include <cstdint>

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

}  // namespace octoreach::detail
