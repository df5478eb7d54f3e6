#include "common/thread_pool.hpp"

#include <condition_variable>

namespace octoreach::detail {
namespace {

thread_local bool t_inside_task = false;

struct TaskScope {
  TaskScope() { t_inside_task = true; }
  ~TaskScope() { t_inside_task = false; }
};

// Workers wait for a new generation, run their share, and count down. One job at a time; a caller
// that finds the pool busy falls back to threads of its own.
class ThreadPool {
 public:
  bool try_run(int n, const std::function<void(int)>& task) {
    std::unique_lock<std::mutex> job(job_mutex_, std::try_to_lock);
    if (!job) return false;
    grow(n - 1);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      task_ = &task;
      active_ = n - 1;
      pending_ = n - 1;
      ++generation_;
    }
    start_.notify_all();
    {
      TaskScope scope;
      task(0);
    }
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return pending_ == 0; });
    task_ = nullptr;
    return true;
  }

 private:
  void grow(int workers) {
    while (static_cast<int>(threads_.size()) < workers) {
      int index = static_cast<int>(threads_.size());
      threads_.emplace_back([this, index] { work(index); });
      threads_.back().detach();  // the pool lives as long as the process
    }
  }

  void work(int index) {
    std::uint64_t seen = 0;
    for (;;) {
      const std::function<void(int)>* task = nullptr;
      {
        std::unique_lock<std::mutex> lock(mutex_);
        start_.wait(lock, [&] { return generation_ != seen; });
        seen = generation_;
        if (index >= active_) continue;
        task = task_;
      }
      {
        TaskScope scope;
        (*task)(index + 1);
      }
      std::lock_guard<std::mutex> lock(mutex_);
      if (--pending_ == 0) done_.notify_one();
    }
  }

  std::mutex job_mutex_, mutex_;
  std::condition_variable start_, done_;
  std::vector<std::thread> threads_;
  const std::function<void(int)>* task_ = nullptr;
  int active_ = 0, pending_ = 0;
  std::uint64_t generation_ = 0;
};

ThreadPool& pool() {
  static ThreadPool* instance = new ThreadPool();  // never destroyed: workers may outlive static destructors
  return *instance;
}

}  // namespace

bool inside_pool_task() { return t_inside_task; }

void run_on_pool(int n, const std::function<void(int)>& task) {
  if (n <= 1) {
    TaskScope scope;
    task(0);
    return;
  }
  if (pool().try_run(n, task)) return;
  std::vector<std::thread> threads;
  for (int t = 1; t < n; ++t)
    threads.emplace_back([&task, t] {
      TaskScope scope;
      task(t);
    });
  {
    TaskScope scope;
    task(0);
  }
  for (auto& th : threads) th.join();
}

}  // namespace octoreach::detail
