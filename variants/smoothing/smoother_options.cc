// Names and validation of the smoother's options (the CLI's --loss and --solver values).
#include <cmath>

#include <fmt/core.h>

#include "variants/smoothing/smoother.h"

namespace arbor {

bool SmootherOptions::validate(std::string* why) const {
  const auto fail = [&](std::string message) {
    if (why) *why = std::move(message);
    return false;
  };
  if (!(loss_scale > 0.0) || !std::isfinite(loss_scale)) return fail(fmt::format("loss scale {} must be > 0", loss_scale));
  if (max_iterations < 0) return fail(fmt::format("max_iterations {} must be >= 0", max_iterations));
  if (warm_start_poses < 0 || warm_start_iterations < 0) return fail("warm start sizes must be >= 0");
  if (pose_marginals_max_poses < 0) return fail("pose_marginals_max_poses must be >= 0");
  if (threads < 1) return fail(fmt::format("threads {} must be >= 1", threads));
  if (!(function_tolerance >= 0.0) || !(gradient_tolerance >= 0.0) || !(parameter_tolerance >= 0.0))
    return fail("tolerances must be >= 0");
  if (!(motion_floor_variance.array() >= 0.0).all()) return fail("motion_floor_variance must be >= 0");
  if (!(prior_floor_sigma > 0.0)) return fail("prior_floor_sigma must be > 0");
  return true;
}

}  // namespace arbor
