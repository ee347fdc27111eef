#pragma once
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

#include "common/PeakMemory.h"

namespace baker {

// A progress bar with an ETA on stderr, for work that takes longer than a second. It stays
// silent when stderr is not a terminal (logs, CI) or when turned off (--quiet). Thread-safe:
// workers report from any thread; redraws are throttled.
class ProgressBar {
 public:
  ProgressBar(std::string label, bool enabled);
  ~ProgressBar();
  void update(std::int64_t done, std::int64_t total);

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point start_, lastDraw_;
  std::mutex mutex_;
};

}  // namespace baker
