#pragma once
// Internal: a reader-writer mutex that lets a waiting writer in first. std::shared_mutex on glibc
// prefers readers, so threads that query a map in a loop could keep an insert waiting for ever;
// here a reader that finds a writer waiting steps back until the writer has had its turn.
#include <atomic>
#include <chrono>
#include <shared_mutex>
#include <thread>

namespace octoreach::detail {

class SharedMutex {
 public:
  void lock() {
    waiting_.fetch_add(1, std::memory_order_acq_rel);
    m_.lock();
    waiting_.fetch_sub(1, std::memory_order_acq_rel);
  }
  void unlock() { m_.unlock(); }
  void lock_shared() {
    for (int spins = 0; waiting_.load(std::memory_order_acquire) > 0; ++spins) {
      if (spins < 64)
        std::this_thread::yield();
      else
        std::this_thread::sleep_for(std::chrono::microseconds(50));
    }
    m_.lock_shared();
  }
  void unlock_shared() { m_.unlock_shared(); }

 private:
  std::shared_mutex m_;
  std::atomic<int> waiting_{0};
};

}  // namespace octoreach::detail
