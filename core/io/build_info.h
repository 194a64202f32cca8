// What produced a result: commit, compiler, host. Stamped into every result file.
#ifndef ARBOR_CORE_IO_BUILD_INFO_H_
#define ARBOR_CORE_IO_BUILD_INFO_H_

#include <string>

namespace arbor {

std::string git_commit();   // short hash, '+' appended when the tree had uncommitted changes when built
std::string compiler();     // e.g. "gcc-12.2.0"
std::string host_name();
std::string build_type();   // "release" or "debug" (NDEBUG), plus "+asan"/"+tsan" when sanitized

}  // namespace arbor

#endif  // ARBOR_CORE_IO_BUILD_INFO_H_
