// Always-on and debug-only invariant checks for the hot paths (engine, maps, association).
// A violated invariant would otherwise give a silently wrong number, so it aborts with file and line.
#ifndef ARBOR_CORE_CHECK_H_
#define ARBOR_CORE_CHECK_H_

#include <cstdio>
#include <cstdlib>

#include <fmt/core.h>

namespace arbor::internal {
[[noreturn]] inline void check_failed(const char* file, int line, const char* expr, const std::string& message) {
  std::fprintf(stderr, "%s:%d: check failed: %s %s\n", file, line, expr, message.c_str());
  std::abort();
}
}  // namespace arbor::internal

#define ARBOR_CHECK(cond, ...)                                                                    \
  do {                                                                                            \
    if (!(cond)) [[unlikely]]                                                                     \
      ::arbor::internal::check_failed(__FILE__, __LINE__, #cond, ::fmt::format("" __VA_ARGS__)); \
  } while (false)

#ifdef NDEBUG
#define ARBOR_DCHECK(cond, ...) \
  do {                          \
  } while (false)
#else
#define ARBOR_DCHECK(cond, ...) ARBOR_CHECK(cond, __VA_ARGS__)
#endif

#endif  // ARBOR_CORE_CHECK_H_
