// Atomic whole-file writes and durable appends (see atomic_file.h).
#include "core/io/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <signal.h>

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/core.h>

#include "core/io/input_error.h"

namespace arbor {
namespace {

// Writes all of text; false (errno set) when the system refuses (a full disk, a quota).
bool write_all(int fd, std::string_view text) {
  while (!text.empty()) {
    const ssize_t n = ::write(fd, text.data(), text.size());
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    text.remove_prefix(static_cast<std::size_t>(n));
  }
  return ::fsync(fd) == 0 || errno == EINVAL;  // EINVAL: a special file (a pipe, /dev/null) cannot sync
}

}  // namespace

void remove_orphaned_temporaries(const std::string& path, std::string_view tag) {
  const std::filesystem::path target(path);
  const std::string prefix = target.filename().string() + "." + std::string(tag) + ".";
  const std::filesystem::path dir = target.has_parent_path() ? target.parent_path() : ".";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    const std::string name = entry.path().filename().string();
    if (name.size() <= prefix.size() || name.compare(0, prefix.size(), prefix) != 0) continue;
    pid_t pid = 0;
    const char* digits = name.c_str() + prefix.size();
    const auto [end, parsed] = std::from_chars(digits, name.c_str() + name.size(), pid);
    if (parsed != std::errc() || *end != '\0' || pid <= 0) continue;
    if (::kill(pid, 0) != 0 && errno == ESRCH) std::filesystem::remove(entry.path(), error);
  }
}

void write_file_atomically(const std::string& path, std::string_view text) {
  const std::filesystem::path target(path);
  if (target.has_parent_path()) std::filesystem::create_directories(target.parent_path());
  remove_orphaned_temporaries(path, "tmp");
  const std::string temp = fmt::format("{}.tmp.{}", path, ::getpid());
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw EnvironmentError(path, fmt::format("cannot write: {}", std::strerror(errno)));
  const bool written = write_all(fd, text);
  const int write_error = errno;
  ::close(fd);
  if (!written) {
    ::unlink(temp.c_str());  // a failed write leaves no temporary behind
    throw EnvironmentError(path, fmt::format("write failed: {}", std::strerror(write_error)));
  }
  if (std::rename(temp.c_str(), path.c_str()) != 0) {
    const int rename_error = errno;
    ::unlink(temp.c_str());
    throw EnvironmentError(path, fmt::format("cannot rename into place: {}", std::strerror(rename_error)));
  }
}

void forget_finished_run(const std::string& out_dir) {
  if (out_dir.empty()) return;
  std::error_code error;
  const std::filesystem::path result = std::filesystem::path(out_dir) / "result.json";
  std::filesystem::remove(result, error);
  if (error) throw EnvironmentError(result.string(), fmt::format("cannot remove the previous run's result: {}", error.message()));
}

void prepare_run_directory(const std::string& out_dir) {
  if (out_dir.empty()) return;
  std::error_code error;
  std::filesystem::create_directories(out_dir, error);
  if (error) throw EnvironmentError(out_dir, fmt::format("cannot create the output directory: {}", error.message()));
  forget_finished_run(out_dir);
  const std::string probe = (std::filesystem::path(out_dir) / fmt::format(".write_check.{}", ::getpid())).string();
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  if (fd < 0) throw EnvironmentError(out_dir, fmt::format("cannot write in the output directory: {}", std::strerror(errno)));
  ::close(fd);
  ::unlink(probe.c_str());
}

void append_line_durably(const std::string& path, std::string_view text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
  if (fd < 0) throw EnvironmentError(path, fmt::format("cannot append: {}", std::strerror(errno)));
  const bool written = write_all(fd, text);
  const int write_error = errno;
  ::close(fd);
  if (!written) throw EnvironmentError(path, fmt::format("append failed: {}", std::strerror(write_error)));
}

}  // namespace arbor
