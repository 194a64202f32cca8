// The hostile-input harness: a case is a valid scenario (w.scn, simulated), an edit of it or another input, an
// `arbor` command and the exit status and message it must give. It checks the contract of docs/cli.md "Exit
// status and budgets": exit 0 with finite output, or exit 2 (input, options) / 1 (environment) with a message
// naming file:line:field where the input has lines, and no result.json after a failure. Shared by the suites
// of issue 14 (hostile_input_test.cc) and of the later review (hostile_review_test.cc).
#ifndef ARBOR_TESTS_EXPERIMENTS_HOSTILE_HARNESS_H_
#define ARBOR_TESTS_EXPERIMENTS_HOSTILE_HARNESS_H_

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <ostream>
#include <regex>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "tests/support/scratch.h"

namespace arbor::hostile {

namespace fs = std::filesystem;
inline const std::string kShippedData = std::string(ARBOR_SOURCE_DIR) + "/tests/data/";

inline void write_text(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// dst = src with the first match of pattern (ECMAScript, per line with multiline anchors) replaced.
inline void mutate(const fs::path& src, const fs::path& dst, const std::string& pattern, const std::string& replacement) {
  const std::string text = testing::read_file(src.string());
  const std::regex re(pattern, std::regex::ECMAScript | std::regex::multiline);
  ASSERT_TRUE(std::regex_search(text, re)) << pattern << " not in " << src;
  write_text(dst, std::regex_replace(text, re, replacement, std::regex_constants::format_first_only));
}

struct HostileCase {
  std::string klass;  // the class of issue 14's list, or the review finding's id, it belongs to
  std::string name;
  // Prepares files in dir (a fresh scratch directory holding w.scn, a valid scenario).
  std::function<void(const fs::path& dir)> setup;
  std::string command;  // {arbor} and {dir} are substituted
  int exit_code;
  std::string message;  // a regex the output must match (empty: none)
  // Exit 0: result.json exists and nothing in the run's files is NaN or infinite.
  // Otherwise: {dir}/out/result.json does not exist.
};

inline std::ostream& operator<<(std::ostream& os, const HostileCase& c) { return os << c.klass << "/" << c.name; }

inline void no_setup(const fs::path&) {}

// A scenario edit: w.scn with the first line matching pattern replaced.
inline std::function<void(const fs::path&)> scenario_edit(std::string pattern, std::string replacement) {
  return [=](const fs::path& dir) { mutate(dir / "w.scn", dir / "w.scn", pattern, replacement); };
}

// A copy of a shipped dataset with one file's first line matching pattern replaced.
inline std::function<void(const fs::path&)> dataset_edit(std::string dataset, std::string file, std::string pattern,
                                                  std::string replacement) {
  return [=](const fs::path& dir) {
    fs::copy(kShippedData + dataset, dir / dataset, fs::copy_options::recursive);
    mutate(dir / dataset / file, dir / dataset / file, pattern, replacement);
  };
}

inline std::function<void(const fs::path&)> file(std::string name, std::string text) {
  return [=](const fs::path& dir) { write_text(dir / name, text); };
}

// A shipped dataset with one line edited, then converted: `arbor convert` refuses it (exit 2) with a message
// matching `message`. The dataset's folder name with hyphens is its --from name.
inline HostileCase converted_dataset_edit(std::string klass, std::string name, std::string dataset, std::string file,
                                          std::string pattern, std::string replacement, std::string message) {
  std::string from = dataset;
  std::replace(from.begin(), from.end(), '_', '-');
  const std::string command = "{arbor} convert --from " + from + " --input {dir}/" + dataset + " --out {dir}/out/" +
                              dataset + ".scn";
  return {std::move(klass), std::move(name),
          dataset_edit(std::move(dataset), std::move(file), std::move(pattern), std::move(replacement)), command, 2,
          std::move(message)};
}

inline std::string substitute(std::string command, const fs::path& dir) {
  for (const auto& [key, value] : {std::pair<std::string, std::string>{"{arbor}", testing::arbor_binary()},
                                   std::pair<std::string, std::string>{"{dir}", dir.string()}}) {
    for (std::size_t at; (at = command.find(key)) != std::string::npos;) command.replace(at, key.size(), value);
  }
  return command;
}

inline bool has_non_finite_text(const std::string& text) {
  static const std::regex non_finite(R"((^|[ ,\t:\[])[-+]?(nan|inf|NaN|Inf|infinity)([ ,\t\n\]]|$))",
                                     std::regex::multiline);
  return std::regex_search(text, non_finite);
}


// Runs the case in a fresh scratch directory holding w.scn, a valid scenario, and checks its contract.
inline void expect_exits_cleanly(const HostileCase& c) {
  const fs::path dir = testing::scratch_dir("hostile_" + c.klass + "_" + c.name);
  ASSERT_EQ(testing::run_command(testing::arbor_binary() + " simulate --landmarks 20 --steps 8 --clutter 1 --out " +
                                 (dir / "w.scn").string()).exit_code, 0);
  c.setup(dir);
  const auto r = testing::run_command(substitute(c.command, dir));
  EXPECT_EQ(r.exit_code, c.exit_code) << r.output;
  if (!c.message.empty()) {
    EXPECT_TRUE(std::regex_search(r.output, std::regex(c.message))) << c.message << "\n" << r.output;
  }
  // CLI11's own range checks printed the largest double in full, 309 digits.
  EXPECT_FALSE(std::regex_search(r.output, std::regex("[0-9]{40}"))) << r.output;
  const fs::path result = dir / "out" / "result.json";
  if (c.exit_code != 0) {
    EXPECT_FALSE(fs::exists(result)) << "a failed command left " << result;
  } else if (c.command.rfind("{arbor} run ", 0) == 0 || c.command.rfind("{arbor} smooth ", 0) == 0) {
    ASSERT_TRUE(fs::exists(result)) << r.output;
    for (const char* name : {"result.json", "trajectory.tum", "map.csv"})
      EXPECT_FALSE(has_non_finite_text(testing::read_file((dir / "out" / name).string()))) << name << " holds NaN or inf";
  }
}

}  // namespace arbor::hostile

#endif  // ARBOR_TESTS_EXPERIMENTS_HOSTILE_HARNESS_H_
