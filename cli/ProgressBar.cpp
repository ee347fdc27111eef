#include "cli/ProgressBar.h"

#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>

namespace baker {

ProgressBar::ProgressBar(std::string label, bool enabled)
    : label_(std::move(label)), enabled_(enabled && ::isatty(STDERR_FILENO)), start_(std::chrono::steady_clock::now()) {}

ProgressBar::~ProgressBar() {
  if (drawn_) std::fputs("\r\033[K", stderr);  // leave the line to the summary
}

void ProgressBar::update(std::int64_t done, std::int64_t total) {
  if (!enabled_ || total <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  const std::lock_guard<std::mutex> lock(mutex_);
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  // Nothing for bakes under a second, then at most ten redraws a second.
  if (elapsed < 1.0 || (drawn_ && now - lastDraw_ < std::chrono::milliseconds(100))) return;
  lastDraw_ = now;
  drawn_ = true;
  const double fraction = double(done) / double(total);
  constexpr int kWidth = 30;
  const int filled = int(fraction * kWidth);
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : 0.0;
  std::fputs(fmt::format("\r{} [{}{}] {:5.1f} %  {:.0f} s left\033[K", label_, std::string(filled, '#'),
                         std::string(kWidth - filled, '.'), 100.0 * fraction, eta)
                 .c_str(),
             stderr);
  std::fflush(stderr);
}

}  // namespace baker
