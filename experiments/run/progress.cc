// Progress line rendering.
#include "experiments/run/progress.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>

#include <fmt/core.h>

namespace arbor {

ProgressLine::ProgressLine(bool enabled) : enabled_(enabled), terminal_(::isatty(STDERR_FILENO) != 0) {}

bool ProgressLine::due(double fraction) const {
  if (!enabled_) return false;
  if (!shown_) return true;
  const auto since = std::chrono::steady_clock::now() - last_;
  if (terminal_) return since >= std::chrono::milliseconds(500);
  return static_cast<int>(std::floor(10.0 * fraction)) != last_tenth_ || since >= std::chrono::seconds(10);
}

void ProgressLine::show(const std::string& text, double fraction, bool last) {
  if (!enabled_ || (!last && !due(fraction))) return;
  shown_ = true;
  last_ = std::chrono::steady_clock::now();
  last_tenth_ = static_cast<int>(std::floor(10.0 * fraction));
  if (terminal_) fmt::print(stderr, "\r{}\033[K{}", text, last ? "\n" : "");
  else fmt::print(stderr, "{}\n", text);
  std::fflush(stderr);
}

Progress::Progress(std::string label, std::int64_t total, bool enabled)
    : label_(std::move(label)), total_(total), enabled_(enabled && total > 0),
      start_(std::chrono::steady_clock::now()), line_(enabled_) {}

void Progress::show(std::int64_t done, const std::string& extra) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double left = done > 0 ? elapsed * (total_ - done) / done : 0.0;
  line_.show(fmt::format("{}: {}/{} ({:.0f}%) elapsed {:.1f}s, ~{:.1f}s left{}{}", label_, done, total_,
                         100.0 * done / total_, elapsed, left, extra.empty() ? "" : ", ", extra),
             static_cast<double>(done) / total_, false);
}

void Progress::finish(const std::string& extra) {
  if (!enabled_) return;
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  line_.show(fmt::format("{}: {}/{} done in {:.1f}s{}{}", label_, total_, total_, elapsed, extra.empty() ? "" : ", ",
                         extra),
             1.0, true);
}

}  // namespace arbor
