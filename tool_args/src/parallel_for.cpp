#include "tool_args/parallel_for.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace multirobot_audio::tools {

void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& work,
                 const std::function<void(int, int)>& progress) {
  if (count == 0) return;
  if (threads <= 0) threads = static_cast<int>(std::thread::hardware_concurrency());
  threads = std::max(1, std::min<int>(threads, static_cast<int>(count)));
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  int done = 0;
  std::exception_ptr failure;
  auto worker = [&]() {
    for (std::size_t i = next++; i < count; i = next++) {
      try {
        work(i);
      } catch (...) {
        std::lock_guard<std::mutex> guard(lock);
        if (!failure) failure = std::current_exception();
        next = count;
        return;
      }
      std::lock_guard<std::mutex> guard(lock);
      ++done;
      if (progress) progress(done, static_cast<int>(count));
    }
  };
  std::vector<std::thread> pool;
  for (int k = 0; k < threads; ++k) pool.emplace_back(worker);
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace multirobot_audio::tools
