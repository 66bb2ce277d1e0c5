#include "parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace tracer {

int resolve_threads(int threads) {
  if (threads > 0) return threads;
  return std::max(1, int(std::thread::hardware_concurrency()));
}

void parallel_items(int threads, int count, const std::function<void(int worker, int item)>& body) {
  if (count <= 0) return;
  threads = std::clamp(threads, 1, count);
  std::atomic<int> next{0};
  std::exception_ptr failure;
  std::mutex failure_mutex;

  auto worker = [&](int index) {
    try {
      for (int item = next++; item < count; item = next++) body(index, item);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failure_mutex);
      if (!failure) failure = std::current_exception();
      next = count;  // the others take no new item
    }
  };

  std::vector<std::thread> pool;
  pool.reserve(std::size_t(threads - 1));
  try {
    for (int i = 1; i < threads; ++i) pool.emplace_back(worker, i);
  } catch (...) {  // no thread to be had: stop those started, then report it
    next = count;
    for (std::thread& t : pool) t.join();
    throw;
  }
  worker(0);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace tracer
