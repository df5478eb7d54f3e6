#pragma once
// Private helper: a static-partition parallel for over [0, n) with std::thread.
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace octoreach::detail {

inline int default_threads(int requested) {
  if (requested > 0) return requested;
  unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(hw);
}

/// Runs body(i, thread_id) for i in [0, n). Items are handed out in small
/// dynamic chunks so uneven work still keeps every core busy. Exceptions in a
/// worker are rethrown in the caller.
template <class Body>
void parallel_for(std::size_t n, int threads, Body&& body, std::size_t chunk = 16) {
  threads = std::max(1, std::min<int>(default_threads(threads), static_cast<int>((n + chunk - 1) / chunk)));
  if (threads <= 1) {
    for (std::size_t i = 0; i < n; ++i) body(i, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr error;
  std::mutex error_mutex;
  auto worker = [&](int tid) {
    try {
      for (;;) {
        std::size_t start = next.fetch_add(chunk);
        if (start >= n) break;
        std::size_t end = std::min(n, start + chunk);
        for (std::size_t i = start; i < end; ++i) body(i, tid);
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(error_mutex);
      if (!error) error = std::current_exception();
      next.store(n);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(worker, t);
  worker(0);
  for (auto& th : pool) th.join();
  if (error) std::rethrow_exception(error);
}

}  // namespace octoreach::detail
