#pragma once
// Internal: one process-wide pool of worker threads, started once and reused by every parallel
// loop (the next-best-view search runs many small loops; starting threads per call cost more
// than the work). parallel_for hands out items in small dynamic chunks so uneven work keeps
// every core busy; exceptions in a worker are rethrown in the caller.
//
// Rules: body(i, tid) gets tid in [0, threads) (index per-thread scratch with it). A parallel_for
// called from inside a pool task runs serially on that thread (no nested fan-out, no deadlock).
// Two callers from different threads at once: the second runs on its own threads.
// Cancellation (common/cancel.hpp) is polled after every chunk; a Cancelled is rethrown like any error.
#include <algorithm>
#include <atomic>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "common/cancel.hpp"

namespace octoreach::detail {

/// \brief Number of threads for a request: `requested` if > 0, else the hardware's.
inline int default_threads(int requested) {
  if (requested > 0) return requested;
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

/// \brief Runs task(tid) for tid in [0, n): tid 0 on the calling thread, the others on pool
/// workers; returns when all are done. `task` must not throw.
void run_on_pool(int n, const std::function<void(int)>& task);

/// \brief True on a thread that is running a pool task (nested loops run serially there).
bool inside_pool_task();

/// Runs body(i, thread_id) for i in [0, n).
template <class Body>
void parallel_for(std::size_t n, int threads, Body&& body, std::size_t chunk = 16) {
  threads = std::max(1, std::min<int>(default_threads(threads), static_cast<int>((n + chunk - 1) / chunk)));
  if (threads <= 1 || inside_pool_task()) {
    for (std::size_t i = 0; i < n; ++i) {
      body(i, 0);
      poll_cancel();
    }
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};  // set on the first error: the other threads stop at their next poll
  std::exception_ptr error;
  std::mutex error_mutex;
  run_on_pool(threads, [&](int tid) {
    StopScope stop_scope(&stop);
    try {
      for (;;) {
        std::size_t start = next.fetch_add(chunk);
        if (start >= n) break;
        std::size_t end = std::min(n, start + chunk);
        for (std::size_t i = start; i < end; ++i) body(i, tid);
        poll_cancel();  // a no-op on workers and outside cancellable work
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(n);
      stop.store(true);
    }
  });
  if (error) std::rethrow_exception(error);
}

}  // namespace octoreach::detail
