// What the dataset loaders share: CSV headers, clock conversion, time order, and the readers of the two
// file kinds more than one dataset has (Ackermann dead reckoning, a GPS track).
#ifndef ARBOR_EXPERIMENTS_LOADERS_LOADER_UTIL_H_
#define ARBOR_EXPERIMENTS_LOADERS_LOADER_UTIL_H_

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/text_reader.h"
#include "core/types/timed_pose.h"
#include "experiments/loaders/step_merger.h"

namespace arbor {

// Reads the first line and checks that it is the expected CSV header (a wrong file in the right place
// otherwise parses as numbers with the wrong meaning).
void expect_csv_header(TextReader& in, std::initializer_list<std::string_view> names);

// Seconds (as logged, millisecond resolution) to integer milliseconds, so that "same time stamp" and the
// merge of controls and scans compare exactly.
inline std::int64_t seconds_to_ms(double seconds) { return static_cast<std::int64_t>(std::llround(seconds * 1000.0)); }

// Joins a directory and a file name.
std::string join_path(const std::string& dir, std::string_view file);

// Checks time order line by line. strict: each time must exceed the previous one; otherwise equal times are
// allowed (several rows of one scan). Going backwards is always an error naming file, line and field.
class TimeOrder {
 public:
  explicit TimeOrder(bool strict) : strict_(strict) {}
  // Returns true when t equals the previous time (only possible when not strict).
  bool check(const TextReader& in, std::int64_t t_ms, std::string_view field);

 private:
  bool strict_;
  bool first_ = true;
  std::int64_t last_ms_ = 0;
};

// The time column of a loader's CSV file: its name, and whether it holds integer milliseconds (else seconds
// as a decimal number).
struct TimeColumn {
  std::string_view name;
  bool milliseconds = false;
};

// Ackermann dead reckoning: columns time, speed [m/s], steering [rad], strictly increasing in time. A
// steering angle at or past 1.2 rad is an error: tan() of it is meaningless near 90 degrees, and both
// datasets' cars lock at about 35 degrees. Throws InputError naming file, line and field.
std::vector<ControlSample> read_ackermann_dead_reckoning(const std::string& path, TimeColumn time,
                                                         std::string_view speed);

// A position track (GPS): columns time, x, y [m], strictly increasing in time; times are returned in
// seconds after origin_ms. Throws InputError naming file, line and field.
std::vector<TimedPosition> read_position_track(const std::string& path, TimeColumn time, std::string_view x,
                                               std::string_view y, std::int64_t origin_ms = 0);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_LOADER_UTIL_H_
