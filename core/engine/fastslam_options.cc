// FastSlamOptions names and validation.
#include "core/engine/fastslam_options.h"

#include <fmt/core.h>

namespace arbor {

std::string_view to_string(FilterVersion version) {
  return version == FilterVersion::kFastSlam1 ? "fastslam1" : "fastslam2";
}

bool from_string(std::string_view name, FilterVersion* version) {
  if (name == "fastslam1") *version = FilterVersion::kFastSlam1;
  else if (name == "fastslam2") *version = FilterVersion::kFastSlam2;
  else return false;
  return true;
}

std::string_view to_string(MotionSampling sampling) {
  return sampling == MotionSampling::kPerScan ? "per-scan" : "per-control";
}

bool from_string(std::string_view name, MotionSampling* sampling) {
  if (name == "per-scan") *sampling = MotionSampling::kPerScan;
  else if (name == "per-control") *sampling = MotionSampling::kPerControl;
  else return false;
  return true;
}

std::string_view to_string(Likelihood likelihood) {
  return likelihood == Likelihood::kGaussian ? "gaussian" : "student-t";
}

bool from_string(std::string_view name, Likelihood* likelihood) {
  if (name == "gaussian") *likelihood = Likelihood::kGaussian;
  else if (name == "student-t") *likelihood = Likelihood::kStudentT;
  else return false;
  return true;
}

std::string FastSlamOptions::validate() const {
  if (particles < 1) return fmt::format("particles must be at least 1 (got {})", particles);
  if (threads < 0) return fmt::format("threads must be 0 (all) or positive (got {})", threads);
  if (!(resample_threshold >= 0.0 && resample_threshold <= 1.0))
    return fmt::format("resample threshold must lie in [0, 1] (got {})", resample_threshold);
  const double p = association.gate_probability, q = association.new_landmark_probability;
  if (!(p > 0.0 && p < 1.0)) return fmt::format("gate probability must lie in (0, 1) (got {})", p);
  if (!(q > 0.0 && q < 1.0)) return fmt::format("new-landmark probability must lie in (0, 1) (got {})", q);
  if (!(log_odds_hit > 0.0 && log_odds_miss >= 0.0)) return "log-odds hit must be positive and miss non-negative";
  if (!(student_dof > 0.0 && student_dof <= 1e6)) return fmt::format("Student-t dof must lie in (0, 1e6] (got {})", student_dof);
  const double k = association.known_gate_probability;
  if (!(k > 0.0 && k <= 1.0)) return fmt::format("known-association gate probability must lie in (0, 1] (got {})", k);
  return "";
}

}  // namespace arbor
