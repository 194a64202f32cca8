// Robust noise estimates from ground truth: measurement residuals and replayed motion windows.
#include "experiments/loaders/noise_estimation.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/metrics/run_statistics.h"
#include "core/models/range_bearing_model.h"

namespace arbor {

double robust_sigma(std::vector<double> e) {
  if (e.empty()) return 0.0;
  const double m = median(e);
  for (double& x : e) x = std::abs(x - m);
  return 1.4826 * median(std::move(e));
}

double tail_respecting_sigma(const std::vector<double>& e, double center, double robust) {
  if (e.empty()) return 0.0;
  double sigma = robust;
  // Two passes: drop residuals beyond 5 sigma (gross outliers), take the standard deviation of the rest.
  for (int pass = 0; pass < 2 && sigma > 0.0; ++pass) {
    double sum = 0.0;
    std::int64_t n = 0;
    for (double x : e)
      if (std::abs(x - center) <= 5.0 * sigma) {
        sum += (x - center) * (x - center);
        ++n;
      }
    if (n == 0) break;
    sigma = std::sqrt(sum / n);
  }
  return sigma;
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
  out.mad_sigma_range_m = dof_scale * robust_sigma(er);
  out.mad_sigma_bearing_rad = dof_scale * robust_sigma(eb);
  out.sigma_range_m = dof_scale * tail_respecting_sigma(er, out.range_bias_m, out.mad_sigma_range_m / dof_scale);
  out.sigma_bearing_rad = dof_scale * tail_respecting_sigma(eb, out.bearing_bias_rad, out.mad_sigma_bearing_rad / dof_scale);
  std::int64_t outliers = 0, beyond3 = 0;
  for (std::size_t i = 0; i < er.size(); ++i) {
    const double r = std::abs(er[i] - out.range_bias_m) / out.sigma_range_m;
    const double b = std::abs(eb[i] - out.bearing_bias_rad) / out.sigma_bearing_rad;
    outliers += r > 5.0 || b > 5.0;
    beyond3 += r > 3.0 || b > 3.0;
  }
  out.outlier_fraction = static_cast<double>(outliers) / static_cast<double>(er.size());
  out.beyond_3sigma_fraction = static_cast<double>(beyond3) / static_cast<double>(er.size());
  return out;
}

namespace {

// The scenario's motion model with unit density on one noise source (0: speed, 1: turn rate or steering) and
// none on the others: its process noise is d Q_d / d q for that source.
MotionModel unit_noise_model(MotionModel m, int source) {
  m.odometry = m.velocity = TwistNoise{0.0, 0.0, 0.0, 0.0, 0.0};
  m.ackermann = AckermannNoise{0.0, 0.0};
  if (m.kind == MotionModelKind::kAckermann) {
    (source == 0 ? m.ackermann.q_v : m.ackermann.q_steer) = 1.0;
  } else {
    TwistNoise& n = m.kind == MotionModelKind::kOdometry ? m.odometry : m.velocity;
    (source == 0 ? n.q_v : n.q_omega) = 1.0;
  }
  return m;
}

// Fits q from ratios r_i = e_i^2 / A_i (each a chi-square(1) times q): q_mad = median / 0.4549, then the mean
// of the ratios within 5 sigma (25 q), twice.
void fit_density(const std::vector<double>& ratio, double* q_mad, double* q) {
  constexpr double kMedianChi2OneDof = 0.4549;
  *q_mad = median(ratio) / kMedianChi2OneDof;
  *q = *q_mad;
  for (int pass = 0; pass < 2 && *q > 0.0; ++pass) {
    double sum = 0.0;
    std::int64_t n = 0;
    for (double r : ratio)
      if (r <= 25.0 * *q) {
        sum += r;
        ++n;
      }
    if (n > 0) *q = sum / n;
  }
}

}  // namespace

MotionNoiseEstimate estimate_motion_noise(const Scenario& s, double window_s, double min_speed) {
  std::vector<double> ratio_1, ratio_2;
  const MotionModel unit_1 = unit_noise_model(s.motion, 0), unit_2 = unit_noise_model(s.motion, 1);
  const std::size_t n = s.steps.size();
  std::size_t i = 0;
  while (i < n) {
    if (!s.steps[i].truth_pose) {
      ++i;
      continue;
    }
    // Replay from step i's truth pose until a truth step at least window_s later; A and B are the window's
    // predicted covariance per unit density of each source.
    Pose2 x = *s.steps[i].truth_pose;
    Mat3 A = Mat3::Zero(), B = Mat3::Zero();
    double distance = 0.0;
    std::size_t j = i + 1;
    for (; j < n; ++j) {
      const Vec3& u = s.steps[j].control;
      const double dt = s.steps[j].time_s - s.steps[j - 1].time_s;
      Pose2 x_a = x, x_b = x;
      unit_1.predict(&x_a, &A, u, dt);
      unit_2.predict(&x_b, &B, u, dt);
      distance += (x_a.position() - x.position()).norm();
      x = x_a;
      if (s.steps[j].truth_pose && s.steps[j].time_s - s.steps[i].time_s >= window_s) break;
    }
    if (j >= n) break;
    const double duration = s.steps[j].time_s - s.steps[i].time_s;
    // Windows across long gaps in the truth (or in the controls) say nothing about the noise.
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
  fit_density(ratio_1, &out.mad_q_1, &out.q_1);
  fit_density(ratio_2, &out.mad_q_2, &out.q_2);
  return out;
}

void apply_noise_estimates(const MeasurementNoiseEstimate& measurement, const MotionNoiseEstimate& motion,
                           Scenario* scenario) {
  if (measurement.count > 0) {
    scenario->sensor.sigma_range_m = measurement.sigma_range_m;
    scenario->sensor.sigma_bearing_rad = measurement.sigma_bearing_rad;
  }
  if (motion.windows > 0) {
    scenario->motion.velocity.q_v = motion.q_1;
    scenario->motion.velocity.q_omega = motion.q_2;
  }
}

}  // namespace arbor
