// TextReader: tokenised line reading with precise error locations.
#include "core/io/text_reader.h"

#include <charconv>
#include <cmath>
#include <filesystem>
#include <system_error>

#include <fmt/core.h>

namespace arbor {

TextReader::TextReader(std::string path, std::string_view separators, char comment_char)
    : path_(std::move(path)), separators_(separators), comment_char_(comment_char), in_(path_) {
  std::error_code error;
  if (std::filesystem::is_directory(path_, error)) throw InputError(path_, 0, "", "is a directory, not a file");
  if (!in_) throw InputError(path_, 0, "", "cannot open file for reading");
}

bool TextReader::next() {
  while (std::getline(in_, line_)) {
    ++line_number_;
    if (!line_.empty() && line_.back() == '\r') line_.pop_back();
    // A UTF-8 byte-order mark (some Windows editors write one) is no part of the first field; kept, it made
    // every reader report a different, wrong problem with a header that looked right (hostile C4).
    if (line_number_ == 1 && line_.starts_with("\xEF\xBB\xBF")) line_.erase(0, 3);
    fields_.clear();
    std::string_view rest(line_);
    const auto is_separator = [&](char c) {
      return c == ' ' || c == '\t' || separators_.find(c) != std::string::npos;
    };
    std::size_t i = 0;
    while (i < rest.size() && (rest[i] == ' ' || rest[i] == '\t')) ++i;
    if (i == rest.size() || rest[i] == comment_char_) continue;
    const bool strict_separators = !separators_.empty();
    while (i <= rest.size()) {
      std::size_t j = i;
      while (j < rest.size() && !is_separator(rest[j])) ++j;
      if (j > i || (strict_separators && j < rest.size() && separators_.find(rest[j]) != std::string::npos))
        fields_.push_back(rest.substr(i, j - i));
      if (j >= rest.size()) break;
      // With explicit separators (CSV) one separator ends one field, so "a,,b" has an empty middle field.
      i = j + 1;
      if (!strict_separators)
        while (i < rest.size() && is_separator(rest[i])) ++i;
    }
    if (strict_separators && !line_.empty() && separators_.find(line_.back()) != std::string::npos)
      fields_.push_back(std::string_view());
    return true;
  }
  return false;
}

void TextReader::expect_fields(std::size_t min, std::size_t max, std::string_view what) const {
  if (fields_.size() < min || fields_.size() > max) {
    const std::string expected = min == max ? fmt::format("{}", min) : fmt::format("{} to {}", min, max);
    const std::string field = fields_.size() < min ? fmt::format("#{}", fields_.size() + 1) : fmt::format("#{}", max + 1);
    throw InputError(path_, line_number_, field,
                     fmt::format("{} line has {} fields, expected {} (truncated or malformed line?)", what,
                                 fields_.size(), expected));
  }
}

bool parse_finite_double(std::string_view text, double* value) {
  if (text.empty()) return false;
  bool negative = false;
  if (text.front() == '+' || text.front() == '-') {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  // Every form strtod reads (docs/scenario_format.md), hex floats included; from_chars wants those without
  // their 0x prefix.
  auto format = std::chars_format::general;
  if (text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X')) {
    text.remove_prefix(2);
    format = std::chars_format::hex;
  }
  if (text.empty() || text.front() == '+' || text.front() == '-') return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), *value, format);
  if (negative) *value = -*value;
  return ec == std::errc() && end == text.data() + text.size() && std::isfinite(*value);
}

double TextReader::number(std::size_t i, std::string_view name) const {
  if (i >= fields_.size()) fail(name, "missing value");
  double value;
  if (!parse_finite_double(fields_[i], &value))
    fail(name, fmt::format("'{}' is not a finite number", fields_[i]));
  return value;
}

std::int64_t TextReader::integer(std::size_t i, std::string_view name) const {
  if (i >= fields_.size()) fail(name, "missing value");
  std::int64_t value;
  std::string_view text = fields_[i];
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size())
    fail(name, fmt::format("'{}' is not an integer", text));
  return value;
}

void TextReader::fail(std::string_view field_name, const std::string& message) const {
  throw InputError(path_, line_number_, std::string(field_name), message);
}

}  // namespace arbor
