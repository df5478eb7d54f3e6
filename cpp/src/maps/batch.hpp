#pragma once
// Private: the batched lookups of the map classes (many poses or points at once): on the shared
// pool for batches large enough to pay for it, else on the calling thread.
#include <cstddef>

#include "../common/thread_pool.hpp"

namespace octoreach::detail {

/// Runs f(i) for i in [0, n): every core above 20000 lookups, one thread below.
template <class F>
void batch_lookup(std::size_t n, F&& f) {
  parallel_for(n, n > 20000 ? 0 : 1, [&](std::size_t i, int) { f(i); }, 4096);
}

}  // namespace octoreach::detail
