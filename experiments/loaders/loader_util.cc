// Shared loader checks and readers.
#include "experiments/loaders/loader_util.h"

#include <cmath>

#include <fmt/core.h>

#include "core/io/field_limits.h"

namespace arbor {

void expect_csv_header(TextReader& in, std::initializer_list<std::string_view> names) {
  std::string expected;
  for (std::string_view n : names) {
    if (!expected.empty()) expected += ',';
    expected += n;
  }
  if (!in.next()) throw InputError(in.path(), 0, "header", fmt::format("empty file (expected the header '{}')", expected));
  in.expect_fields(names.size(), names.size(), "header");
  std::size_t i = 0;
  for (std::string_view n : names) {
    if (in.field(i) != n)
      in.fail(std::string(n), fmt::format("header column {} is '{}', expected '{}' (header '{}')", i + 1, in.field(i), n, expected));
    ++i;
  }
}

std::string join_path(const std::string& dir, std::string_view file) {
  if (dir.empty()) return std::string(file);
  return dir.back() == '/' ? dir + std::string(file) : dir + "/" + std::string(file);
}

bool TimeOrder::check(const TextReader& in, std::int64_t t_ms, std::string_view field) {
  bool same = false;
  if (!first_) {
    if (t_ms < last_ms_)
      in.fail(field, fmt::format("time goes backwards ({:.3f} s after {:.3f} s)", t_ms / 1000.0, last_ms_ / 1000.0));
    same = t_ms == last_ms_;
    if (same && strict_) in.fail(field, fmt::format("time {:.3f} s repeats the previous line's", t_ms / 1000.0));
  }
  first_ = false;
  last_ms_ = t_ms;
  return same;
}

namespace {

// The row's time in milliseconds, and the value as written (seconds or milliseconds).
std::int64_t read_time_ms(TextReader& in, TimeColumn time, double* as_written) {
  if (time.milliseconds) {
    const std::int64_t t = time_ms_field(in, 0, time.name);
    *as_written = static_cast<double>(t);
    return t;
  }
  *as_written = time_field(in, 0, time.name);
  return seconds_to_ms(*as_written);
}

}  // namespace

std::vector<ControlSample> read_ackermann_dead_reckoning(const std::string& path, TimeColumn time,
                                                         std::string_view speed) {
  TextReader in(path, ",");
  expect_csv_header(in, {time.name, speed, "steering_rad"});
  TimeOrder order(/*strict=*/true);
  std::vector<ControlSample> controls;
  while (in.next()) {
    in.expect_fields(3, 3, "dead-reckoning");
    ControlSample c;
    double written = 0.0;
    c.time_ms = read_time_ms(in, time, &written);
    order.check(in, c.time_ms, time.name);
    c.u1 = control_field(in, 1, speed);
    c.u2 = in.number(2, "steering_rad");
    if (std::abs(c.u2) >= scenario_limits::kMaxSteering) in.fail("steering_rad", fmt::format("steering {} rad is outside the vehicle's range", c.u2));
    c.line = in.line_number();
    controls.push_back(c);
  }
  if (controls.empty()) throw InputError(path, in.line_number(), "", "no dead-reckoning samples");
  return controls;
}

std::vector<TimedPosition> read_position_track(const std::string& path, TimeColumn time, std::string_view x,
                                               std::string_view y, std::int64_t origin_ms) {
  TextReader in(path, ",");
  expect_csv_header(in, {time.name, x, y});
  TimeOrder order(/*strict=*/true);
  std::vector<TimedPosition> track;
  while (in.next()) {
    in.expect_fields(3, 3, "GPS");
    double written = 0.0;
    const std::int64_t t_ms = read_time_ms(in, time, &written);
    order.check(in, t_ms, time.name);
    // Seconds as written keep their digits (no round trip through milliseconds).
    const double t_s = time.milliseconds ? (t_ms - origin_ms) / 1000.0 : written - origin_ms / 1000.0;
    track.push_back({t_s, {coordinate_field(in, 1, x), coordinate_field(in, 2, y)}});
  }
  return track;
}

}  // namespace arbor
