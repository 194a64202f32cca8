// A one-line progress report on stderr for long work: done/total, elapsed, estimated time left.
#ifndef ARBOR_EXPERIMENTS_RUN_PROGRESS_H_
#define ARBOR_EXPERIMENTS_RUN_PROGRESS_H_

#include <chrono>
#include <cstdint>
#include <string>

namespace arbor {

class Progress {
 public:
  Progress(std::string label, std::int64_t total, bool enabled);
  // Reports at most every half second (every 10 % when stderr is not a terminal).
  void update(std::int64_t done, const std::string& extra = "");
  void finish(const std::string& extra = "");

 private:
  std::string label_;
  std::int64_t total_;
  bool enabled_, terminal_;
  std::chrono::steady_clock::time_point start_, last_;
  std::int64_t last_decile_ = -1;
};

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_RUN_PROGRESS_H_
