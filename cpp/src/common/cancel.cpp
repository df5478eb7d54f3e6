#include "common/cancel.hpp"

#include <atomic>
#include <chrono>

#include "octoreach/types.hpp"

namespace octoreach {

namespace {
std::atomic<CancelCheck> g_check{nullptr};
thread_local bool t_cancellable = false;
thread_local const std::atomic<bool>* t_stop = nullptr;
thread_local std::chrono::steady_clock::time_point t_next_poll{};
constexpr std::chrono::milliseconds kPollInterval{100};
}  // namespace

void set_cancel_check(CancelCheck check) { g_check.store(check); }

namespace detail {

CancellableScope::CancellableScope() : previous_(t_cancellable) { t_cancellable = true; }
CancellableScope::~CancellableScope() { t_cancellable = previous_; }

StopScope::StopScope(const std::atomic<bool>* stop) : previous_(t_stop) { t_stop = stop; }
StopScope::~StopScope() { t_stop = previous_; }

void poll_cancel(const char* what) {
  if (t_stop && t_stop->load(std::memory_order_relaxed)) throw Cancelled(what);
  if (!t_cancellable) return;
  const auto now = std::chrono::steady_clock::now();
  if (now < t_next_poll) return;
  t_next_poll = now + kPollInterval;
  CancelCheck check = g_check.load(std::memory_order_relaxed);
  if (check && check()) throw Cancelled(what);
}

}  // namespace detail
}  // namespace octoreach
