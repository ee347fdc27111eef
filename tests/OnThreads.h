#pragma once
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

namespace baker::test {

// Runs `work` on `threads` threads even on a machine with fewer cores: TBB's global limit alone
// stays at the core count, so the work gets an arena of its own with the limit raised to match.
template <typename Work>
auto onThreads(int threads, const Work& work) {
  const tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
  tbb::task_arena arena(threads);
  return arena.execute(work);
}

}  // namespace baker::test
