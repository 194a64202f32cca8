// Shared loader checks.
#include "experiments/loaders/loader_util.h"

#include <cmath>

#include <fmt/core.h>

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

}  // namespace arbor
