// Helpers shared by the experiment-level tests: simulated worlds, scratch directories, files, running the
// arbor binary.
#ifndef ARBOR_TESTS_EXPERIMENTS_TEST_SUPPORT_H_
#define ARBOR_TESTS_EXPERIMENTS_TEST_SUPPORT_H_

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"

namespace arbor::testing {

// The default simulated world (experiments/sim/simulator.h), world and noise from one seed.
inline Scenario simulated_world(std::uint64_t seed, int scans, double clutter = 0.0, int controls_per_scan = 1) {
  SimulationOptions o;
  o.seed = o.world.seed = seed;
  o.steps = scans;
  o.clutter_rate = clutter;
  o.controls_per_scan = controls_per_scan;
  return simulate(o);
}

// A FastSLAM run with the default map and association (naive, known) and these settings.
inline RunConfig fastslam_config(FilterVersion version, int particles, std::uint64_t seed, int threads) {
  RunConfig c;
  c.options.version = version;
  c.options.particles = particles;
  c.options.seed = seed;
  c.options.threads = threads;
  return c;
}

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

#endif  // ARBOR_TESTS_EXPERIMENTS_TEST_SUPPORT_H_
