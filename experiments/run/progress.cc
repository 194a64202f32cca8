// Progress line rendering.
#include "experiments/run/progress.h"

#include <unistd.h>

#include <cstdio>

#include <fmt/core.h>

namespace arbor {

Progress::Progress(std::string label, std::int64_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled), terminal_(::isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()), last_(start_) {}

void Progress::update(std::int64_t done, const std::string& extra) {
  if (!enabled_ || total_ <= 0) return;
  const auto now = std::chrono::steady_clock::now();
  const std::int64_t decile = done * 10 / total_;
  if (terminal_ ? now - last_ < std::chrono::milliseconds(500) : decile == last_decile_) return;
  last_ = now;
  last_decile_ = decile;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double left = done > 0 ? elapsed * (total_ - done) / done : 0.0;
  fmt::print(stderr, "{}{}: {}/{} ({:.0f}%) elapsed {:.1f}s, ~{:.1f}s left{}{}", terminal_ ? "\r" : "", label_, done,
             total_, 100.0 * done / total_, elapsed, left, extra.empty() ? "" : ", ", extra);
  if (!terminal_) fmt::print(stderr, "\n");
  std::fflush(stderr);
}

void Progress::finish(const std::string& extra) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  fmt::print(stderr, "{}{}: {}/{} done in {:.1f}s{}{}\n", terminal_ ? "\r" : "", label_, total_, total_, elapsed,
             extra.empty() ? "" : ", ", extra);
}

}  // namespace arbor
