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
#include "octoreach/types.hpp"

namespace octoreach::detail {

/// Runs f(i) for i in [0, n) in chunks of `chunk`: on `threads` threads (0: every core), or with threads < 0
/// on every core above 20000 lookups and one thread below.
template <class F>
void batch_lookup(std::size_t n, F&& f, int threads = -1, std::size_t chunk = 4096) {
  parallel_for(n, threads >= 0 ? threads : (n > 20000 ? 0 : 1), [&](std::size_t i, int) { f(i); }, chunk);
}

/// Lowers `first_bad` to i (the first invalid row of a batch, whichever thread finds it).
inline void note_bad_row(std::atomic<std::size_t>& first_bad, std::size_t i) {
  std::size_t seen = first_bad.load(std::memory_order_relaxed);
  while (i < seen && !first_bad.compare_exchange_weak(seen, i, std::memory_order_relaxed)) {
  }
}

/// The rule of a batch's rows: finite numbers (points, planar poses), or with width 16 a row-major 4x4 pose that
/// must also be a rigid transform (octoreach::is_rigid: a sheared or scaled rotation would give an answer for a
/// pose nobody meant). valid() is checked as a row is read (inside the parallel loop: the batch is touched once);
/// raise() throws std::invalid_argument "<what> <i> is not finite<hint>", or with width 16 check_rigid's message
/// (its hint unused).
struct RowRule {
  int width;
  const char* what;
  const char* hint;
  bool valid(const double* r) const {
    if (width == 16) return is_rigid(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(r));
    bool finite = true;
    for (int k = 0; k < width; ++k) finite &= std::isfinite(r[k]);
    return finite;
  }
  [[noreturn]] void raise(const double* r, std::size_t i) const {
    const std::string name = std::string(what) + " " + std::to_string(i);
    if (width != 16) throw std::invalid_argument(name + " is not finite" + hint);
    check_rigid(Eigen::Matrix4d(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(r)), name);
    // valid() refused the row: a pose at the tolerance's edge that check_rigid's copy rounds the other way
    throw std::invalid_argument(name + " is not a rigid transform (at the edge of the tolerance)");
  }
};

/// batch_lookup over n rows of `width` doubles, each row checked by RowRule as it is read; f(i) runs only for valid
/// rows. Throws naming the first invalid row afterwards: a NaN would fall outside every voxel and read 0, a wrong
/// answer.
template <class F>
void batch_lookup_valid(const double* rows, std::size_t n, int width, const char* what, const char* hint, F&& f,
                        int threads = -1, std::size_t chunk = 4096) {
  const RowRule rule{width, what, hint};
  std::atomic<std::size_t> first_bad{n};
  batch_lookup(n, [&](std::size_t i) {
    if (rule.valid(rows + i * static_cast<std::size_t>(width))) f(i);
    else note_bad_row(first_bad, i);
  }, threads, chunk);
  const std::size_t bad = first_bad.load();
  if (bad < n) rule.raise(rows + bad * static_cast<std::size_t>(width), bad);
}

/// batch_lookup_valid over groups of up to `group` rows: g(i0, i1, valid) with valid[k] for row i0 + k, so that
/// a lookup can work out every row's table address first and prefetch it before reading (a large table's misses
/// then overlap instead of stalling one row after another). group is at most 64.
template <class G>
void batch_lookup_valid_groups(const double* rows, std::size_t n, int width, const char* what, const char* hint,
                               std::size_t group, G&& g) {
  const RowRule rule{width, what, hint};
  std::atomic<std::size_t> first_bad{n};
  const std::size_t groups = (n + group - 1) / group;
  batch_lookup(groups, [&](std::size_t gi) {
    const std::size_t i0 = gi * group, i1 = std::min(n, i0 + group);
    bool valid[64];
    for (std::size_t i = i0; i < i1; ++i) {
      valid[i - i0] = rule.valid(rows + i * static_cast<std::size_t>(width));
      if (!valid[i - i0]) note_bad_row(first_bad, i);
    }
    g(i0, i1, valid);
  }, groups * group > 20000 ? 0 : 1, std::max<std::size_t>(1, 4096 / group));
  const std::size_t bad = first_bad.load();
  if (bad < n) rule.raise(rows + bad * static_cast<std::size_t>(width), bad);
}

}  // namespace octoreach::detail
