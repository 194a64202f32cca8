// Arbor's two exception types. InputError: bad input or options, with the file, line and field that were
// wrong; thrown only at the input boundary (readers, loaders, CLI); main() prints it and exits with status 2.
// EnvironmentError: the input was fine but the machine failed us (a full disk, a file that cannot be
// written); main() exits with status 1, as for every other failure.
#ifndef ARBOR_CORE_IO_INPUT_ERROR_H_
#define ARBOR_CORE_IO_INPUT_ERROR_H_

#include <stdexcept>
#include <string>

#include <fmt/core.h>

namespace arbor {

class InputError : public std::runtime_error {
 public:
  // line = 0 means the error concerns the whole file (missing, empty) or an option; field may be empty.
  InputError(std::string file, int line, std::string field, const std::string& message)
      : std::runtime_error(format(file, line, field, message)), file_(std::move(file)), line_(line),
        field_(std::move(field)), message_(message) {}

  const std::string& file() const { return file_; }
  int line() const { return line_; }
  const std::string& field() const { return field_; }
  const std::string& message() const { return message_; }  // what() without the location

 private:
  static std::string format(const std::string& file, int line, const std::string& field, const std::string& message) {
    std::string where = file;
    if (line > 0) where += fmt::format(":{}", line);
    // An option has no file: "field 'x': ...", not ": field 'x': ...".
    if (!field.empty()) where += fmt::format("{}field '{}'", where.empty() ? "" : ": ", field);
    return where.empty() ? message : where + ": " + message;
  }
  std::string file_;
  int line_;
  std::string field_;
  std::string message_;
};

class EnvironmentError : public std::runtime_error {
 public:
  EnvironmentError(const std::string& path, const std::string& message) : std::runtime_error(path + ": " + message) {}
};

}  // namespace arbor

#endif  // ARBOR_CORE_IO_INPUT_ERROR_H_
