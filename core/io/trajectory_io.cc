// TUM trajectory and map CSV reading and writing.
#include "core/io/trajectory_io.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

#include <fmt/core.h>

#include "core/check.h"
#include "core/io/atomic_file.h"
#include "core/io/field_limits.h"
#include "core/io/input_error.h"
#include "core/io/text_reader.h"

namespace arbor {

std::string format_tum(const std::vector<TimedPose>& trajectory) {
  std::string out;
  for (std::size_t i = 0; i < trajectory.size(); ++i) {
    const TimedPose& p = trajectory[i];
    ARBOR_CHECK(i == 0 || p.time_s >= trajectory[i - 1].time_s, "TUM row {} goes back in time: {} after {}", i,
                p.time_s, trajectory[i - 1].time_s);
    // A TUM file maps a time to one pose, and evo refuses a repeated time ("not ascending"). Several states can
    // share a time (the initial pose and a first scan at the start time, controls with equal stamps); the
    // last of them is the estimate at that time, so only it is written.
    if (i + 1 < trajectory.size() && trajectory[i + 1].time_s == p.time_s) continue;
    // A rotation by theta about z: q = (0, 0, sin(theta/2), cos(theta/2)).
    fmt::format_to(std::back_inserter(out), "{} {} {} 0 0 0 {} {}\n", p.time_s, p.pose.x, p.pose.y,
                   std::sin(0.5 * p.pose.theta), std::cos(0.5 * p.pose.theta));
  }
  return out;
}

void write_tum(const std::string& path, const std::vector<TimedPose>& trajectory) {
  write_file_atomically(path, format_tum(trajectory));
}

std::vector<TimedPose> read_tum(const std::string& path) {
  TextReader in(path);
  std::vector<TimedPose> out;
  while (in.next()) {
    in.expect_fields(8, 8, "TUM pose");
    TimedPose p;
    // Bounded: a pose of 1e300 m reached the smoother's solver as inf (hostile C2).
    constexpr double kMax = scenario_limits::kMaxEstimateCoordinate;
    p.time_s = time_field(in, 0, "t");
    p.pose.x = number_within(in, 1, "x", -kMax, kMax);
    p.pose.y = number_within(in, 2, "y", -kMax, kMax);
    const double qz = in.number(6, "qz"), qw = in.number(7, "qw");
    p.pose.theta = wrap_angle(2.0 * std::atan2(qz, qw));
    if (!out.empty() && p.time_s < out.back().time_s) in.fail("t", "time goes backwards");
    out.push_back(p);
  }
  // Every run writes at least its start pose; an empty file was taken as no trajectory at all.
  if (out.empty()) throw InputError(path, 0, "", "no poses (a TUM trajectory has one 't x y z qx qy qz qw' line per pose)");
  return out;
}

namespace {

constexpr const char* kMapColumns[] = {"id", "x", "y", "cov_xx", "cov_xy", "cov_yy", "log_odds", "signature", "truth_label"};

// "id,x,y,...": the header the writer writes and the reader expects.
std::string map_header() {
  std::string header;
  for (const char* column : kMapColumns) header += std::string(header.empty() ? "" : ",") + column;
  return header;
}

// The whole header, column by column: a map whose x and y columns were swapped was read as it stood (hostile B2).
void expect_map_header(const TextReader& in) {
  const std::string expected = map_header();
  bool matches = in.field_count() == std::size(kMapColumns);
  for (std::size_t i = 0; matches && i < in.field_count(); ++i) matches = in.field(i) == kMapColumns[i];
  if (!matches) in.fail("header", fmt::format("expected the map.csv header '{}', got '{}'", expected, in.line()));
}

double map_variance_field(const TextReader& in, std::size_t i, std::string_view name) {
  const double v = in.number(i, name);
  if (!(v > 0.0)) in.fail(name, "must be > 0");
  if (v < scenario_limits::kMinMapVariance || v > scenario_limits::kMaxMapVariance)
    in.fail(name, fmt::format("{} is outside the format's limits [{}, {}]", v, scenario_limits::kMinMapVariance,
                              scenario_limits::kMaxMapVariance));
  return v;
}

}  // namespace

std::string format_map_csv(const std::vector<Landmark>& map) {
  std::string out = map_header() + "\n";
  for (const Landmark& lm : map) {
    fmt::format_to(std::back_inserter(out), "{},{},{},{},{},{},{},{},{}\n", lm.id, lm.mean.x(), lm.mean.y(),
                   lm.cov(0, 0), lm.cov(0, 1), lm.cov(1, 1), lm.log_odds,
                   std::isnan(lm.signature) ? std::string() : fmt::format("{}", lm.signature), lm.truth_label);
  }
  return out;
}

void write_map_csv(const std::string& path, const std::vector<Landmark>& map) {
  write_file_atomically(path, format_map_csv(map));
}

std::vector<Landmark> read_map_csv(const std::string& path) {
  TextReader in(path, ",");
  std::vector<Landmark> out;
  if (!in.next()) throw InputError(path, 0, "header", "empty file (expected the map.csv header)");
  expect_map_header(in);
  std::unordered_map<LandmarkId, int> landmark_line;  // id -> the line that gave it
  while (in.next()) {
    in.expect_fields(9, 9, "map.csv");
    Landmark lm;
    lm.id = landmark_id_field(in, 0, "id");
    const auto [first, inserted] = landmark_line.emplace(lm.id, in.line_number());
    if (!inserted) in.fail("id", fmt::format("landmark {} is listed twice (first at line {})", lm.id, first->second));
    lm.mean = {coordinate_field(in, 1, "x"), coordinate_field(in, 2, "y")};
    const double xx = map_variance_field(in, 3, "cov_xx");
    const double xy = number_within(in, 4, "cov_xy", -scenario_limits::kMaxMapVariance, scenario_limits::kMaxMapVariance);
    lm.cov << xx, xy, xy, map_variance_field(in, 5, "cov_yy");
    // A landmark's covariance must be positive definite: every update inverts it (through S = H P H^T + R).
    if (!(lm.cov(0, 0) * lm.cov(1, 1) - lm.cov(0, 1) * lm.cov(0, 1) > 0.0))
      in.fail("cov_xy", "the covariance is not positive definite (cov_xy^2 >= cov_xx * cov_yy)");
    lm.log_odds = static_cast<float>(in.number(6, "log_odds"));
    if (!std::isfinite(lm.log_odds)) in.fail("log_odds", "out of float range");
    // The scenario's signature limit: 1e300 became inf as a float, and the run's own map.csv was then refused.
    if (!in.field(7).empty())
      lm.signature = static_cast<float>(number_within(in, 7, "signature", -scenario_limits::kMaxSignature, scenario_limits::kMaxSignature));
    const std::int64_t label = in.integer(8, "truth_label");
    if (label < -1 || label > std::numeric_limits<std::int32_t>::max()) in.fail("truth_label", "must be -1 (none) or a true id");
    lm.truth_label = static_cast<std::int32_t>(label);
    out.push_back(lm);
  }
  return out;
}

}  // namespace arbor
