// Line-by-line reading of whitespace- or comma-separated text with errors that name file, line and field.
// Every reader in Arbor (scenarios, datasets, association problems, sweep specs) parses through this.
#ifndef ARBOR_CORE_IO_TEXT_READER_H_
#define ARBOR_CORE_IO_TEXT_READER_H_

#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/input_error.h"

namespace arbor {

class TextReader {
 public:
  // Opens path; throws InputError(path, 0, "", "cannot open ...") when it cannot be read.
  // separators: the characters that split fields (whitespace always does). Lines whose first non-blank
  // character is comment_char, and blank lines, are skipped.
  explicit TextReader(std::string path, std::string_view separators = "", char comment_char = '#');

  // Advances to the next data line; false at end of file.
  bool next();

  int line_number() const { return line_number_; }
  const std::string& path() const { return path_; }
  const std::string& line() const { return line_; }
  std::size_t field_count() const { return fields_.size(); }
  std::string_view field(std::size_t i) const { return fields_.at(i); }

  // Throws unless the line has between min and max fields; names the line's kind in the message.
  void expect_fields(std::size_t min, std::size_t max, std::string_view what) const;
  // Field i as a finite double / an integer; the error names `name`, the field's meaning.
  double number(std::size_t i, std::string_view name) const;
  std::int64_t integer(std::size_t i, std::string_view name) const;
  // An error at the current line.
  [[noreturn]] void fail(std::string_view field_name, const std::string& message) const;

 private:
  std::string path_;
  std::string separators_;
  char comment_char_;
  std::ifstream in_;
  std::string line_;
  int line_number_ = 0;
  std::vector<std::string_view> fields_;
};

// Parses a finite double; false on junk, trailing characters, NaN or infinity.
bool parse_finite_double(std::string_view text, double* value);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_TEXT_READER_H_
