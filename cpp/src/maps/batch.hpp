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

/// batch_lookup_finite over groups of up to `group` rows: g(i0, i1, finite) with finite[k] for row i0 + k, so that
/// a lookup can work out every row's table address first and prefetch it before reading (a large table's misses
/// then overlap instead of stalling one row after another). group is at most 64.
template <class G>
void batch_lookup_finite_groups(const double* rows, std::size_t n, int width, const char* what, const char* hint,
                                std::size_t group, G&& g) {
  std::atomic<std::size_t> first_bad{n};
  const std::size_t groups = (n + group - 1) / group;
  batch_lookup(groups, [&](std::size_t gi) {
    const std::size_t i0 = gi * group, i1 = std::min(n, i0 + group);
    bool finite[64];
    for (std::size_t i = i0; i < i1; ++i) {
      const double* r = rows + i * static_cast<std::size_t>(width);
      bool ok = true;
      for (int k = 0; k < width; ++k) ok &= std::isfinite(r[k]);
      finite[i - i0] = ok;
      if (ok) continue;
      std::size_t seen = first_bad.load(std::memory_order_relaxed);
      while (i < seen && !first_bad.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
      }
    }
    g(i0, i1, finite);
  }, groups * group > 20000 ? 0 : 1, std::max<std::size_t>(1, 4096 / group));
  if (first_bad.load() < n)
    throw std::invalid_argument(std::string(what) + " " + std::to_string(first_bad.load()) + " is not finite" + hint);
}

}  // namespace octoreach::detail
