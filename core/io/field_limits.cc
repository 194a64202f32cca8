// Bounded field readers (see field_limits.h).
#include "core/io/field_limits.h"

#include <cstdint>

#include <fmt/core.h>

namespace arbor {

namespace lim = scenario_limits;

double number_within(const TextReader& in, std::size_t i, std::string_view name, double lo, double hi) {
  const double v = in.number(i, name);
  if (v < lo || v > hi) in.fail(name, fmt::format("{} is outside the format's limits [{}, {}]", v, lo, hi));
  return v;
}

double non_negative_within(const TextReader& in, std::size_t i, std::string_view name, double hi) {
  const double v = in.number(i, name);
  if (v < 0.0) in.fail(name, fmt::format("must not be negative, got {}", v));
  if (v > hi) in.fail(name, fmt::format("{} exceeds the format's limit {}", v, hi));
  return v;
}

double coordinate_field(const TextReader& in, std::size_t i, std::string_view name) {
  return number_within(in, i, name, -lim::kMaxCoordinate, lim::kMaxCoordinate);
}

double time_field(const TextReader& in, std::size_t i, std::string_view name) {
  return number_within(in, i, name, -lim::kMaxTime, lim::kMaxTime);
}

double control_field(const TextReader& in, std::size_t i, std::string_view name) {
  return number_within(in, i, name, -lim::kMaxControl, lim::kMaxControl);
}

std::int64_t time_ms_field(const TextReader& in, std::size_t i, std::string_view name) {
  constexpr auto kMaxMs = static_cast<std::int64_t>(lim::kMaxTime * 1000.0);
  const std::int64_t v = in.integer(i, name);
  if (v < -kMaxMs || v > kMaxMs) in.fail(name, fmt::format("{} is outside the format's limits [{}, {}]", v, -kMaxMs, kMaxMs));
  return v;
}

double range_field(const TextReader& in, std::size_t i, std::string_view name) {
  return non_negative_within(in, i, name, lim::kMaxRange);
}

std::int32_t landmark_id_field(const TextReader& in, std::size_t i, std::string_view name) {
  const std::int64_t id = in.integer(i, name);
  if (id < 0 || id > lim::kMaxLandmarkId)
    in.fail(name, fmt::format("landmark id {} is outside [0, {}] (the ids above are the filter's, for the landmarks "
                              "it starts after a prior map's)", id, lim::kMaxLandmarkId));
  return static_cast<std::int32_t>(id);
}

}  // namespace arbor
