// Build and host identification for result files.
#include "core/io/build_info.h"

#include <unistd.h>

#include <fmt/core.h>

namespace arbor {

// git_commit() is generated at build time (cmake/GitCommit.cmake).

std::string compiler() {
#if defined(__clang__)
  return fmt::format("clang-{}.{}.{}", __clang_major__, __clang_minor__, __clang_patchlevel__);
#elif defined(__GNUC__)
  return fmt::format("gcc-{}.{}.{}", __GNUC__, __GNUC_MINOR__, __GNUC_PATCHLEVEL__);
#else
  return "unknown";
#endif
}

std::string host_name() {
  char name[256] = {};
  if (::gethostname(name, sizeof(name) - 1) != 0) return "unknown";
  return name;
}

std::string build_type() {
  std::string type =
#ifdef NDEBUG
      "release";
#else
      "debug";
#endif
#if defined(__SANITIZE_ADDRESS__)
  type += "+asan";
#elif defined(__SANITIZE_THREAD__)
  type += "+tsan";
#endif
  return type;
}

}  // namespace arbor
