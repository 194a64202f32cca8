// Progress on stderr for long work, one policy for every command. On a terminal the line is rewritten in
// place, at most twice a second; in a log file (a sweep's child, a batch job) a line is written when the
// work passes another tenth or ten seconds have gone by, so a log stays short and still shows the job alive.
// The last line is always written.
#ifndef ARBOR_EXPERIMENTS_RUN_PROGRESS_H_
#define ARBOR_EXPERIMENTS_RUN_PROGRESS_H_

#include <chrono>
#include <cstdint>
#include <string>

namespace arbor {

// Free-form text under that policy (the sweep's line).
class ProgressLine {
 public:
  explicit ProgressLine(bool enabled = true);
  // fraction: how much of the work is done, in [0, 1]; last: the final line.
  void show(const std::string& text, double fraction, bool last);
  // Whether show(..., fraction, false) would write now: a caller can skip composing a line nobody sees.
  bool due(double fraction) const;

 private:
  bool enabled_, terminal_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point last_;
  int last_tenth_ = -1;
};

// "label: done/total (p%) elapsed, ~left[, extra]".
class Progress {
 public:
  Progress(std::string label, std::int64_t total, bool enabled);
  // extra: a callable giving the line's tail, called only when the line is due (a filter's loop calls
  // update at every step, and composing lines that the policy drops cost more than some steps).
  template <class Extra>
  void update(std::int64_t done, const Extra& extra) {
    if (enabled_ && line_.due(static_cast<double>(done) / total_)) show(done, extra());
  }
  void finish(const std::string& extra = "");

 private:
  void show(std::int64_t done, const std::string& extra);

  std::string label_;
  std::int64_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_;
  ProgressLine line_;
};

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_PROGRESS_H_
