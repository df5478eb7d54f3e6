#pragma once
// Internal: cancellation of long computations. A computation that may run long marks its thread with
// a CancellableScope; loops on that thread call poll_cancel(), which at most every 100 ms asks the
// process-wide check (octoreach::set_cancel_check; the Python module installs one that reports
// Ctrl-C) and throws Cancelled when it says stop. parallel_for polls after every chunk, so the
// calling thread of a parallel build polls too; pool workers are never marked and pass at the cost of
// one thread_local read. Computations that modify an existing object (ExplorationMap::insert) are
// never marked: cancelling them half-way would leave the object invalid.

#include <atomic>

namespace octoreach::detail {

/// \brief Marks the calling thread's work as cancellable for the scope (scopes nest).
class CancellableScope {
 public:
  CancellableScope();
  ~CancellableScope();
  CancellableScope(const CancellableScope&) = delete;
  CancellableScope& operator=(const CancellableScope&) = delete;

 private:
  bool previous_;
};

/// \brief While it lives, poll_cancel() on this thread also throws Cancelled once `*stop` is set: a parallel
/// loop sets it when one of its threads failed or was cancelled, so the others stop mid-item too.
class StopScope {
 public:
  explicit StopScope(const std::atomic<bool>* stop);
  ~StopScope();
  StopScope(const StopScope&) = delete;
  StopScope& operator=(const StopScope&) = delete;

 private:
  const std::atomic<bool>* previous_;
};

/// \brief Inside a CancellableScope, at most every 100 ms: throws Cancelled(what) if the check says stop.
void poll_cancel(const char* what = "computation cancelled");

}  // namespace octoreach::detail
