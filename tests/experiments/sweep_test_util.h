// Helpers for the sweep and analysis tests: scratch directories and running the real `arbor` binary.
#ifndef ARBOR_TESTS_EXPERIMENTS_SWEEP_TEST_UTIL_H_
#define ARBOR_TESTS_EXPERIMENTS_SWEEP_TEST_UTIL_H_

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "experiments/sweep/child_process.h"

namespace arbor::testing_util {

// A fresh directory under the GoogleTest temp dir, removed at the end of the scope.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& name) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = std::filesystem::path(::testing::TempDir()) /
            ("arbor_" + name + "_" + (info ? std::string(info->name()) : "suite") + "_" + std::to_string(::getpid()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() { std::filesystem::remove_all(path_); }
  std::string operator/(const std::string& leaf) const { return (path_ / leaf).string(); }
  std::string str() const { return path_.string(); }

 private:
  std::filesystem::path path_;
};

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

inline void write_text(const std::string& path, const std::string& text) { std::ofstream(path) << text; }

// The arbor binary of this build ($ARBOR_BINARY_DIR/bin/arbor, set by ctest), or empty.
inline std::string arbor_binary() {
  const char* dir = std::getenv("ARBOR_BINARY_DIR");
  if (!dir) return {};
  const std::string path = std::string(dir) + "/bin/arbor";
  return std::filesystem::exists(path) ? path : std::string();
}

// Runs argv to completion with stdout+stderr in log_path; returns the exit status (-signal if killed).
inline int run_to_end(const std::vector<std::string>& argv, const std::string& log_path) {
  const ChildExit e = wait_child(start_child(argv, log_path));
  return e.signal ? -e.signal : e.exit_code;
}

}  // namespace arbor::testing_util

#endif  // ARBOR_TESTS_EXPERIMENTS_SWEEP_TEST_UTIL_H_
