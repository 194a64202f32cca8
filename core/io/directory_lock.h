// An exclusive lock on an output directory, so that two processes never write one directory's results at once
// (two sweeps into one --out mixed rows of 42 and 25 columns, or ran every run twice).
#ifndef ARBOR_CORE_IO_DIRECTORY_LOCK_H_
#define ARBOR_CORE_IO_DIRECTORY_LOCK_H_

#include <string>

namespace arbor {

// flock(2) on DIR/.lock, held while the object lives. The kernel drops the lock when the process ends, however
// it ends, so a killed sweep never leaves a stale lock behind; the descriptor is close-on-exec, so the runs a
// sweep starts do not hold it. Throws InputError (exit 2) naming DIR when another process holds it.
class DirectoryLock {
 public:
  explicit DirectoryLock(const std::string& dir);
  ~DirectoryLock();
  DirectoryLock(const DirectoryLock&) = delete;
  DirectoryLock& operator=(const DirectoryLock&) = delete;

 private:
  int fd_ = -1;
};

}  // namespace arbor

#endif  // ARBOR_CORE_IO_DIRECTORY_LOCK_H_
