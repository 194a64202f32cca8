// The checks shared by every subcommand's options.
#include "experiments/options/option_checks.h"

#include <cerrno>
#include <charconv>
#include <cstdint>
#include <cmath>
#include <cstdlib>
#include <string>

#include <fmt/format.h>

namespace arbor::cli {
namespace {

// True when text is one number, nothing else (strtod's forms, hex floats included), and finite. strtod, not
// the readers' parse_finite_double: CLI11 takes " 1" as a number, so this check must too.
bool finite_number(const std::string& text) {
  if (text.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno != ERANGE && std::isfinite(value);
}

// True when text is one number, finite or not ("nan", "inf", "1e999"); *value is what strtod read.
bool read_number(const std::string& text, double* value) {
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size();
}

bool any_number(const std::string& text) {
  double value = 0.0;
  return read_number(text, &value);
}

const CLI::Validator kFinite(
    [](std::string& value) {
      return any_number(value) && !finite_number(value) ? "must be a finite number (got " + value + ")"
                                                        : std::string();
    },
    "", "finite");

const CLI::Validator kNonEmpty(
    [](std::string& value) { return value.empty() ? std::string("must not be empty") : std::string(); }, "",
    "non-empty");

}  // namespace

const CLI::Validator& unsigned_number() {
  static const CLI::Validator check(
      [](std::string& value) {
        if (value.find('-') == 0) return "must not be negative (got " + value + ")";
        // CLI11 reads a decimal beyond 2^64 - 1 into an unsigned 64-bit seed as 2^64 - 1, silently.
        std::uint64_t parsed = 0;
        const auto [end, error] = std::from_chars(value.data(), value.data() + value.size(), parsed);
        if (error == std::errc::result_out_of_range)
          return "must be at most 18446744073709551615 (2^64 - 1) (got " + value + ")";
        return std::string();
      },
      "", "unsigned");
  return check;
}

const CLI::Validator& open_probability() {
  static const CLI::Validator check(
      [](std::string& value) {
        double p = 0.0;
        if (!read_number(value, &p)) return std::string();  // the type check says it
        return p > 0.0 && p < 1.0 ? std::string() : "must lie strictly between 0 and 1 (got " + value + ")";
      },
      "", "probability");
  return check;
}

CLI::Validator at_least(double minimum) {
  return CLI::Validator(
      [minimum](std::string& text) {
        double value = 0.0;
        if (!read_number(text, &value) || std::isnan(value) || value >= minimum) return std::string();  // NaN: kFinite
        return fmt::format("must be at least {:g} (got {})", minimum, text);
      },
      fmt::format(">= {:g}", minimum), "at_least");
}

CLI::Validator within(double minimum, double maximum) {
  return CLI::Validator(
      [minimum, maximum](std::string& text) {
        double value = 0.0;
        if (!read_number(text, &value) || std::isnan(value) || (value >= minimum && value <= maximum)) return std::string();
        return fmt::format("must lie in [{:g}, {:g}] (got {})", minimum, maximum, text);
      },
      fmt::format("in [{:g}, {:g}]", minimum, maximum), "within");
}

void apply_common_option_checks(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_expected_max() == 0) continue;  // a flag
    option->check(kNonEmpty);
    if (finite_number(option->get_default_str())) option->check(kFinite);
  }
  for (CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; })) apply_common_option_checks(*sub);
}

}  // namespace arbor::cli
