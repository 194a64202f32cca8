// FastSlamOptions names and validation.
#include "core/engine/fastslam_options.h"

#include <array>
#include <cmath>
#include <utility>

#include <fmt/core.h>

namespace arbor {

std::string FastSlamOptions::validate() const {
  if (particles < 1) return fmt::format("particles must be at least 1 (got {})", particles);
  if (threads < 0) return fmt::format("threads must be 0 (all) or positive (got {})", threads);
  if (!(resample_threshold >= 0.0 && resample_threshold <= 1.0))
    return fmt::format("resample threshold must lie in [0, 1] (got {})", resample_threshold);
  const double p = association.gate_probability, q = association.new_landmark_probability;
  if (!(p > 0.0 && p < 1.0)) return fmt::format("gate probability must lie in (0, 1) (got {})", p);
  if (!(q > 0.0 && q < 1.0)) return fmt::format("new-landmark probability must lie in (0, 1) (got {})", q);
  if (!(log_odds_hit > 0.0 && log_odds_miss >= 0.0)) return "log-odds hit must be positive and miss non-negative";
  if (!std::isfinite(log_odds_confirm)) return "log-odds confirmation level must be finite";
  if (!std::isfinite(log_odds_prune)) return "log-odds pruning level must be finite";
  if (association.max_hypotheses < 1)
    return fmt::format("search budget (max hypotheses) must be at least 1 (got {})", association.max_hypotheses);
  if (association.max_work < 1) return fmt::format("search budget (max work) must be at least 1 (got {})", association.max_work);
  if (provisional_scans < 0) return fmt::format("provisional scans must be 0 (keep) or positive (got {})", provisional_scans);
  if (!(student_dof > 0.0 && student_dof <= 1e6)) return fmt::format("Student-t dof must lie in (0, 1e6] (got {})", student_dof);
  if (relocalize && relocalize_min_pairings < 3)
    return fmt::format("relocalisation needs at least 3 pairings to trust a pose (got {})", relocalize_min_pairings);
  if (provisional_steer_min < 0)
    return fmt::format("provisional steer minimum must be 0 (never) or positive (got {})", provisional_steer_min);
  if (dormant_scans < 1) return fmt::format("dormant scans must be at least 1 (got {})", dormant_scans);
  if (!(loop_drift_m > 0.0 && std::isfinite(loop_drift_m)))
    return fmt::format("loop drift must be positive and finite (got {} m)", loop_drift_m);
  if (!(roughen >= 0.0 && roughen <= 10.0)) return fmt::format("roughening must lie in [0, 10] (got {})", roughen);
  if (!(weight_exponent >= 0.0 && weight_exponent <= 1.0))
    return fmt::format("weight exponent must lie in [0, 1], 0 for the filter's own (got {})", weight_exponent);
  if (move_window < 0 || move_window > 10000)
    return fmt::format("move window must lie in [0, 10000] scans (got {})", move_window);
  if (move_steps < 1 || move_steps > 1000) return fmt::format("move steps must lie in [1, 1000] (got {})", move_steps);
  if (!(move_scale > 0.0 && move_scale <= 100.0)) return fmt::format("move scale must lie in (0, 100] (got {})", move_scale);
  if (move_window > 0 && motion_sampling != MotionSampling::kPerScan)
    return "resample-move (move window > 0) needs per-scan motion sampling";
  if (move_window > 0 && (relocalize || close_loops))
    return "resample-move (move window > 0) does not combine with relocalisation or loop closing";
  const double k = association.known_gate_probability;
  if (!(k > 0.0 && k <= 1.0)) return fmt::format("known-association gate probability must lie in (0, 1] (got {})", k);
  return "";
}

}  // namespace arbor
