// Output files: a failed write is an environment failure (EnvironmentError, exit 1), never "bad input", and
// leaves no temporary file behind.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"

namespace arbor {
namespace {

// /dev/full accepts the open and refuses every write with ENOSPC: a full disk, on demand.
TEST(AtomicFile, AFullDiskIsAnEnvironmentError) {
  EXPECT_THROW(append_line_durably("/dev/full", "row\n"), EnvironmentError);
}

// /proc takes no new files, whoever asks (root included, unlike a read-only directory).
TEST(AtomicFile, AnUnwritableDirectoryIsAnEnvironmentErrorAndLeavesNothing) {
  EXPECT_THROW(write_file_atomically("/proc/arbor_atomic_file_test.txt", "x"), EnvironmentError);
  for (const auto& entry : std::filesystem::directory_iterator("/proc"))
    EXPECT_EQ(entry.path().filename().string().find("arbor_atomic_file_test"), std::string::npos);
}

TEST(AtomicFile, ReplacesTheWholeFile) {
  const std::string path = (std::filesystem::temp_directory_path() / "arbor_atomic_file_test.txt").string();
  write_file_atomically(path, "first, longer text\n");
  write_file_atomically(path, "second\n");
  EXPECT_EQ(std::filesystem::file_size(path), 7u);
  std::filesystem::remove(path);
}

}  // namespace
}  // namespace arbor
