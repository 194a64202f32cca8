// Helpers for tests that write files or run the arbor program: scratch directories, whole files, the build's
// arbor binary and a command's exit status and output.
#ifndef ARBOR_TESTS_SUPPORT_SCRATCH_H_
#define ARBOR_TESTS_SUPPORT_SCRATCH_H_

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace arbor::testing {

// A fresh directory under the system temp dir, named after the test.
inline std::string scratch_dir(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / ("arbor_test_" + name);
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir.string();
}

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Path of the arbor executable of the build these tests belong to (ARBOR_BINARY_DIR overrides it).
inline std::string arbor_binary() {
  const char* dir = std::getenv("ARBOR_BINARY_DIR");
  return std::string(dir ? dir : ARBOR_TEST_BINARY_DIR) + "/bin/arbor";
}

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

inline CommandResult run_command(const std::string& command) {
  CommandResult r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) return r;
  char buffer[4096];
  while (std::size_t n = fread(buffer, 1, sizeof(buffer), pipe)) r.output.append(buffer, n);
  const int status = pclose(pipe);
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

}  // namespace arbor::testing

#endif  // ARBOR_TESTS_SUPPORT_SCRATCH_H_
