#pragma once

#include <algorithm>
#include <atomic>
#include <cstddef>
#include <mutex>
#include <thread>
#include <vector>

namespace audio_propagation {

// Runs job(state, k) for every k in [0, count) on `threads` threads (at least one), each thread
// with its own state from make_state() (a receiver, a copy of the setup: nothing is shared while
// the cells are measured), taking the next cell as it finishes one; after each cell,
// done(finished) runs under a lock with the number of cells finished so far (for progress).
template <class MakeState, class Job, class Done>
void ParallelCells(std::size_t count, int threads, MakeState make_state, Job job, Done done) {
  std::atomic<std::size_t> next{0};
  std::mutex lock;
  std::size_t finished = 0;
  auto work = [&] {
    auto state = make_state();
    for (std::size_t k = next++; k < count; k = next++) {
      job(state, k);
      const std::lock_guard<std::mutex> guard(lock);
      done(++finished);
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < std::max(1, threads); ++t) pool.emplace_back(work);
  for (std::thread& th : pool) th.join();
}

}  // namespace audio_propagation
