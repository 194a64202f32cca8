// Runs one command as a child process with its output in a log file. The sweep runs every experiment this
// way so that a crash, an abort or a runaway allocation in one run cannot take the sweep down.
#ifndef ARBOR_EXPERIMENTS_SWEEP_CHILD_PROCESS_H_
#define ARBOR_EXPERIMENTS_SWEEP_CHILD_PROCESS_H_

#include <sys/types.h>

#include <optional>
#include <string>
#include <vector>

namespace arbor {

// How a child ended.
struct ChildExit {
  int exit_code = -1;  // valid when signal == 0
  int signal = 0;      // the signal that killed it, 0 if it exited
  bool timed_out = false;  // killed by the sweep for running past its time limit
  bool ok() const { return signal == 0 && exit_code == 0; }
  std::string describe() const;  // "exit status 2", "killed by signal 11 (Segmentation fault)"
};

// Starts argv[0] with argv (no shell), stdin from /dev/null, stdout and stderr to log_path (truncated).
// The child dies with the parent (PR_SET_PDEATHSIG), so `kill -9` of a sweep leaves no orphan writing into
// a run directory that the resumed sweep is about to reuse. Throws std::runtime_error when fork fails.
pid_t start_child(const std::vector<std::string>& argv, const std::string& log_path);

// Non-blocking: the exit of any finished child, or nullopt when none has finished.
std::optional<std::pair<pid_t, ChildExit>> poll_children();

// Blocks until `pid` ends.
ChildExit wait_child(pid_t pid);

// The last non-empty line of a log (at most max_chars), for the error column.
std::string last_log_line(const std::string& log_path, std::size_t max_chars = 300);

// The running executable (/proc/self/exe), so the sweep's runs use exactly this build.
std::string self_executable();

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SWEEP_CHILD_PROCESS_H_
