// The progress line composes its text only when the policy will write it (experiments/run/progress.h): a
// filter's loop calls update at every step, and a line composed per step cost more than some steps do.
#include <gtest/gtest.h>
#include <unistd.h>

#include <string>

#include "experiments/run/progress.h"

namespace arbor {
namespace {

TEST(Progress, ComposesTheLineOnlyWhenItIsDue) {
  if (::isatty(STDERR_FILENO)) GTEST_SKIP() << "stderr is a terminal: the line is throttled by time, not by tenths";
  int composed = 0;
  const auto extra = [&] {
    ++composed;
    return std::string("extra");
  };
  Progress quiet("quiet", 1000, /*enabled=*/false);
  for (int done = 1; done <= 1000; ++done) quiet.update(done, extra);
  EXPECT_EQ(composed, 0);

  // In a log, a line is due at the first update and whenever the work passes another tenth (or ten seconds
  // go by, which this loop does not take).
  Progress logged("logged", 1000, /*enabled=*/true);
  for (int done = 1; done <= 1000; ++done) logged.update(done, extra);
  EXPECT_EQ(composed, 11);  // the first update, then at 100, 200, ..., 1000
}

}  // namespace
}  // namespace arbor
