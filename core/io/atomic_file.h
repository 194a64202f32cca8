// Whole-file writes that are atomic: write to a temporary file beside the target, flush, rename.
#ifndef ARBOR_CORE_IO_ATOMIC_FILE_H_
#define ARBOR_CORE_IO_ATOMIC_FILE_H_

#include <string>
#include <string_view>

namespace arbor {

// Replaces path's contents with text; readers see either the old file or the new one, never a mix.
// Throws EnvironmentError (exit 1) when it cannot be written, and leaves no temporary file behind. A
// temporary that a killed writer left (path.tmp.PID, its process gone) is removed by the next write of path.
void write_file_atomically(const std::string& path, std::string_view text);

// Removes the temporaries path.TAG.PID that a killed writer left: those whose process is gone. A live
// writer's temporary stays (a pid reused by another process only keeps a stale file a while longer).
void remove_orphaned_temporaries(const std::string& path, std::string_view tag);

// A run's output directory: result.json is written last, so its presence marks a finished run. A rerun
// into the same directory removes the old one before it starts; were it left, a run that fails half-way
// would leave the old result.json beside new trajectory and map files, and look finished.
void forget_finished_run(const std::string& out_dir);

// Before a run starts: forgets a finished run there (above), creates out_dir and checks that a file can be
// written in it, so an unwritable --out is an error before the run's minutes are spent, not after.
// Throws EnvironmentError (exit 1) naming the directory.
void prepare_run_directory(const std::string& out_dir);

// Appends text (one or more complete lines) with a single write() on an O_APPEND descriptor followed by
// fsync, so a killed process leaves either the whole row or none of it. Throws EnvironmentError on failure.
void append_line_durably(const std::string& path, std::string_view text);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_ATOMIC_FILE_H_
