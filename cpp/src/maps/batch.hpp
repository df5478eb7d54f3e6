#pragma once
// Private: the batched lookups of the map classes (many poses or points at once): on the shared
// pool for batches large enough to pay for it, else on the calling thread.
#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <string>

#include "common/thread_pool.hpp"

namespace octoreach::detail {

/// Runs f(i) for i in [0, n) in chunks of `chunk`: on `threads` threads (0: every core), or with threads < 0
/// on every core above 20000 lookups and one thread below.
template <class F>
void batch_lookup(std::size_t n, F&& f, int threads = -1, std::size_t chunk = 4096) {
  parallel_for(n, threads >= 0 ? threads : (n > 20000 ? 0 : 1), [&](std::size_t i, int) { f(i); }, chunk);
}

/// batch_lookup over n rows of `width` doubles, each row checked for NaN and infinity as it is read
/// (inside the parallel loop: the batch is touched once, the check costs nothing measurable); f(i) runs
/// only for finite rows. Throws std::invalid_argument "<what> <i> is not finite<hint>" naming the first
/// non-finite row afterwards: a NaN would fall outside every voxel and read 0, a wrong answer.
template <class F>
void batch_lookup_finite(const double* rows, std::size_t n, int width, const char* what, const char* hint, F&& f,
                         int threads = -1, std::size_t chunk = 4096) {
  std::atomic<std::size_t> first_bad{n};
  batch_lookup(n, [&](std::size_t i) {
    const double* r = rows + i * static_cast<std::size_t>(width);
    bool finite = true;
    for (int k = 0; k < width; ++k) finite &= std::isfinite(r[k]);
    if (finite) {
      f(i);
      return;
    }
    std::size_t seen = first_bad.load(std::memory_order_relaxed);
    while (i < seen && !first_bad.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
    }
  }, threads, chunk);
  if (first_bad.load() < n)
    throw std::invalid_argument(std::string(what) + " " + std::to_string(first_bad.load()) + " is not finite" + hint);
}

/// batch_lookup_finite in groups of G consecutive rows: f(first, count, finite) with finite[k] true for the
/// finite rows first + k (count <= G). Lookups that read memory at random do one stage for the whole group
/// before the next (prefetching what the next stage reads), so their reads overlap instead of waiting in turn.
template <std::size_t G, class F>
void batch_lookup_finite_groups(const double* rows, std::size_t n, int width, const char* what, const char* hint,
                                F&& f) {
  std::atomic<std::size_t> first_bad{n};
  const std::size_t groups = (n + G - 1) / G;
  batch_lookup(groups, [&](std::size_t g) {
    const std::size_t first = g * G, count = std::min(G, n - first);
    bool finite[G];
    for (std::size_t k = 0; k < count; ++k) {
      const double* r = rows + (first + k) * static_cast<std::size_t>(width);
      bool ok = true;
      for (int c = 0; c < width; ++c) ok &= std::isfinite(r[c]);
      finite[k] = ok;
      if (ok) continue;
      std::size_t seen = first_bad.load(std::memory_order_relaxed);
      while (first + k < seen && !first_bad.compare_exchange_weak(seen, first + k, std::memory_order_relaxed)) {
      }
    }
    f(first, count, static_cast<const bool*>(finite));
  }, n > 20000 ? 0 : 1, std::max<std::size_t>(1, 4096 / G));
  if (first_bad.load() < n)
    throw std::invalid_argument(std::string(what) + " " + std::to_string(first_bad.load()) + " is not finite" + hint);
}

}  // namespace octoreach::detail
