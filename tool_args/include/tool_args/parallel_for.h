#pragma once

#include <cstddef>
#include <functional>

namespace multirobot_audio::tools {

// Calls work(i) for every i in [0, count) spread over `threads` worker threads (0: one per
// core), for batches of independent, deterministic trials whose results must not depend on the
// thread count. `progress` (optional) is called after each item with (done, count), from one
// thread at a time. The first exception stops further items and is rethrown here.
void ParallelFor(std::size_t count, int threads, const std::function<void(std::size_t)>& work,
                 const std::function<void(int, int)>& progress = {});

}  // namespace multirobot_audio::tools
