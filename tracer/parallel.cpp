#include "parallel.h"

#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tracer {

namespace {

/// The process's helper threads, started once and reused by every parallel_items call: starting a
/// thread (its stack mapped and faulted in) took 0.3-0.5 ms before it took its first tile, 0.4% of
/// a 100 ms two-thread render, and a progressive photon render pays it on every pass. Helpers wait
/// blocked between jobs, so they cost no CPU time while idle (the sweep's process CPU clock counts
/// only work). One job runs at a time; a call that finds the pool busy (a nested or concurrent
/// parallel_items), or that runs in a child forked after the pool started (whose copy holds no
/// threads), gets threads of its own instead.
class HelperPool {
 public:
  static HelperPool& instance() {
    static HelperPool pool;
    return pool;
  }

  HelperPool(const HelperPool&) = delete;
  HelperPool& operator=(const HelperPool&) = delete;

  ~HelperPool() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : threads_) t.join();
  }

  /// Starts helpers until there are at least `helpers`; throws what std::thread throws.
  void reserve(int helpers) {
    std::unique_lock<std::mutex> job(job_mutex_, std::try_to_lock);
    if (job.owns_lock() && owned_here()) grow(helpers);
  }

  /// Runs work(1) .. work(helpers) on helper threads while the caller runs work(0), and returns
  /// when every call has returned. `work` must not throw. False, with nothing run, when the pool
  /// cannot take the job (busy, or this is a forked child).
  bool try_run(int helpers, const std::function<void(int)>& work) {
    std::unique_lock<std::mutex> job(job_mutex_, std::try_to_lock);
    if (!job.owns_lock() || !owned_here()) return false;
    grow(helpers);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      work_ = &work;
      wanted_ = helpers;
      finished_ = 0;
      ++generation_;
    }
    wake_.notify_all();
    work(0);
    std::unique_lock<std::mutex> lock(mutex_);
    done_.wait(lock, [&] { return finished_ == wanted_; });
    work_ = nullptr;
    return true;
  }

 private:
  HelperPool() = default;

  bool owned_here() const { return getpid() == owner_; }

  void grow(int helpers) {  // job_mutex_ held
    while (int(threads_.size()) < helpers) {
      const int index = int(threads_.size()) + 1;
      threads_.emplace_back([this, index] { serve(index); });
    }
  }

  void serve(int index) {
    std::uint64_t seen = 0;
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || generation_ != seen; });
      if (stop_) return;
      seen = generation_;
      if (index > wanted_) continue;  // not needed in this job
      const std::function<void(int)>* work = work_;
      lock.unlock();
      (*work)(index);
      lock.lock();
      if (++finished_ == wanted_) done_.notify_one();
    }
  }

  const pid_t owner_ = getpid();
  std::mutex job_mutex_;  ///< Held by the one job in flight.
  std::mutex mutex_;      ///< Guards everything below.
  std::condition_variable wake_, done_;
  std::vector<std::thread> threads_;
  const std::function<void(int)>* work_ = nullptr;
  int wanted_ = 0;    ///< Helpers taking part in the current job.
  int finished_ = 0;  ///< Of them, those that have returned.
  std::uint64_t generation_ = 0;
  bool stop_ = false;
};

/// Runs work(0) .. work(threads - 1) on fresh threads of their own (work(0) on the caller).
void run_on_own_threads(int threads, std::atomic<int>& next, int count,
                        const std::function<void(int)>& work) {
  std::vector<std::thread> pool;
  pool.reserve(std::size_t(threads - 1));
  try {
    for (int i = 1; i < threads; ++i) pool.emplace_back(work, i);
  } catch (...) {  // no thread to be had: stop those started, then report it
    next = count;
    for (std::thread& t : pool) t.join();
    throw;
  }
  work(0);
  for (std::thread& t : pool) t.join();
}

}  // namespace

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

void prepare_threads(int threads) {
  if (threads > 1) HelperPool::instance().reserve(threads - 1);
}

void parallel_items(int threads, int count, const std::function<void(int worker, int item)>& body) {
  if (count <= 0) return;
  threads = std::clamp(threads, 1, count);
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;

  const std::function<void(int)> worker = [&](int index) {
    try {
      for (int item = next++; item < count; item = next++) body(index, item);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = count;  // the others take no new item
    }
  };

  if (threads == 1)
    worker(0);
  else if (!HelperPool::instance().try_run(threads - 1, worker))
    run_on_own_threads(threads, next, count, worker);
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tracer
