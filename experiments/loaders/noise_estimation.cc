// Robust noise estimates from ground truth: measurement residuals and replayed motion windows.
#include "experiments/loaders/noise_estimation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/models/range_bearing_model.h"

namespace arbor {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const std::size_t mid = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + mid, v.end());
  const double upper = v[mid];
  if (v.size() % 2 == 1) return upper;
  return 0.5 * (upper + *std::max_element(v.begin(), v.begin() + mid));
}

double robust_sigma(std::vector<double> e) {
  if (e.empty()) return 0.0;
  const double m = median(e);
  for (double& x : e) x = std::abs(x - m);
  return 1.4826 * median(std::move(e));
}

MeasurementNoiseEstimate estimate_measurement_noise(const Scenario& s, double dof_scale) {
  std::map<std::int32_t, Vec2> landmark;
  for (const auto& l : s.truth_landmarks) landmark[l.id] = l.position;
  std::vector<double> er, eb;
  for (const auto& step : s.steps) {
    if (!step.truth_pose) continue;
    for (const auto& m : step.measurements) {
      const auto it = landmark.find(m.truth_id);
      if (it == landmark.end()) continue;
      const Vec2 e = range_bearing_innovation(m.z(), range_bearing_predict(*step.truth_pose, it->second));
      er.push_back(e.x());
      eb.push_back(e.y());
    }
  }
  MeasurementNoiseEstimate out;
  out.count = static_cast<std::int64_t>(er.size());
  if (er.empty()) return out;
  out.range_bias_m = median(er);
  out.bearing_bias_rad = median(eb);
  out.sigma_range_m = dof_scale * robust_sigma(er);
  out.sigma_bearing_rad = dof_scale * robust_sigma(eb);
  std::int64_t outliers = 0;
  for (std::size_t i = 0; i < er.size(); ++i)
    if (std::abs(er[i] - out.range_bias_m) > 5 * out.sigma_range_m || std::abs(eb[i] - out.bearing_bias_rad) > 5 * out.sigma_bearing_rad)
      ++outliers;
  out.outlier_fraction = static_cast<double>(outliers) / static_cast<double>(er.size());
  return out;
}

MotionNoiseEstimate estimate_motion_noise(const Scenario& s, double window_s, double min_speed) {
  constexpr double kMedianChi2OneDof = 0.4549;
  std::vector<double> ratio_1, ratio_2;
  MotionModel model = s.motion;
  const std::size_t n = s.steps.size();
  std::size_t i = 0;
  while (i < n) {
    if (!s.steps[i].truth_pose) {
      ++i;
      continue;
    }
    // Replay from step i's truth pose until a truth step at least window_s later.
    Pose2 x = *s.steps[i].truth_pose;
    Mat3 A = Mat3::Zero(), B = Mat3::Zero();
    double distance = 0.0;
    std::size_t j = i + 1;
    for (; j < n; ++j) {
      const Vec3& u = s.steps[j].control;
      Mat3 J_x = Mat3::Identity(), J_u = Mat3::Zero();
      x = model.apply(x, u, &J_x, &J_u);
      A = J_x * A * J_x.transpose() + J_u.col(0) * J_u.col(0).transpose();
      B = J_x * B * J_x.transpose() + J_u.col(1) * J_u.col(1).transpose();
      distance += std::abs(u[0]) * u[2];
      if (s.steps[j].truth_pose && s.steps[j].time_s - s.steps[i].time_s >= window_s) break;
    }
    if (j >= n) break;
    const double duration = s.steps[j].time_s - s.steps[i].time_s;
    // Windows across long gaps in the truth (or in the controls) say nothing about per-step noise.
    if (duration <= 2.0 * window_s && distance / duration >= min_speed) {
      const Pose2& truth = *s.steps[j].truth_pose;
      const Vec2 along(std::cos(x.theta), std::sin(x.theta));
      const Vec2 d(truth.x - x.x, truth.y - x.y);
      const double e_along = along.dot(d);
      const double e_theta = wrap_angle(truth.theta - x.theta);
      const double a_along = along.dot(A.topLeftCorner<2, 2>() * along);
      if (a_along > 1e-12) ratio_1.push_back(e_along * e_along / a_along);
      if (B(2, 2) > 1e-12) ratio_2.push_back(e_theta * e_theta / B(2, 2));
    }
    i = j;
  }
  MotionNoiseEstimate out;
  out.windows = static_cast<std::int64_t>(std::min(ratio_1.size(), ratio_2.size()));
  out.sigma_u1 = std::sqrt(median(ratio_1) / kMedianChi2OneDof);
  out.sigma_u2 = std::sqrt(median(ratio_2) / kMedianChi2OneDof);
  return out;
}

}  // namespace arbor
