// Names and validation of the smoother's options (the CLI's --loss and --solver values).
#include <cmath>

#include <fmt/core.h>

#include "core/enum_names.h"
#include "variants/smoothing/smoother.h"

namespace arbor {

namespace {
constexpr EnumNames<SmootherLoss, 3> kLossNames{
    {{SmootherLoss::kNone, "none"}, {SmootherLoss::kHuber, "huber"}, {SmootherLoss::kCauchy, "cauchy"}}};
constexpr EnumNames<SmootherLinearSolver, 2> kSolverNames{{{SmootherLinearSolver::kSparseSchur, "sparse-schur"},
                                                          {SmootherLinearSolver::kSparseNormalCholesky, "sparse-normal-cholesky"}}};
}  // namespace

std::string_view to_string(SmootherLoss loss) { return name_of(kLossNames, loss); }
std::string_view to_string(SmootherLinearSolver solver) { return name_of(kSolverNames, solver); }
bool from_string(std::string_view name, SmootherLoss* loss) { return value_named(kLossNames, name, loss); }
bool from_string(std::string_view name, SmootherLinearSolver* solver) { return value_named(kSolverNames, name, solver); }

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
