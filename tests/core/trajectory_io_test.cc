// TUM output as evo reads it: one pose per time, times strictly ascending (issue 44).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "core/io/trajectory_io.h"

namespace arbor {
namespace {

TEST(FormatTum, RepeatedTimesKeepTheLastPoseOnly) {
  // The initial pose and the first scan's share the start time; the scan's is the estimate at that time.
  const std::vector<TimedPose> trajectory{{0.0, {0, 0, 0}}, {0.0, {1, 0, 0}}, {0.5, {2, 0, 0}}, {0.5, {3, 0, 0}},
                                          {0.5, {4, 0, 0}}, {1.0, {5, 0, 0}}};
  EXPECT_EQ(format_tum(trajectory),
            "0 1 0 0 0 0 0 1\n"
            "0.5 4 0 0 0 0 0 1\n"
            "1 5 0 0 0 0 0 1\n");
}

TEST(FormatTum, HeadingIsARotationAboutZ) {
  // q = (0, 0, sin(theta/2), cos(theta/2)): a unit quaternion, as evo checks.
  EXPECT_EQ(format_tum({{2.0, {0, 0, 3.141592653589793}}}), "2 0 0 0 0 0 1 6.123233995736766e-17\n");
}

TEST(FormatTumDeathTest, TimeGoingBackIsAnError) {
  EXPECT_DEATH(format_tum({{1.0, {}}, {0.5, {}}}), "goes back in time");
}

}  // namespace
}  // namespace arbor
