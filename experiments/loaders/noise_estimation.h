// Noise models estimated from ground truth (DESIGN.md §6; the values are tuning inputs, not dataset facts).
// Robust statistics throughout, because the real data have outliers: sigma = 1.4826 * MAD, the median
// absolute deviation scaled to equal the standard deviation for Gaussian errors.
#ifndef ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_
#define ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_

#include <cstdint>
#include <vector>

#include "core/io/scenario.h"

namespace arbor {

// 1.4826 * median(|e - median(e)|); 0 for an empty input.
double robust_sigma(std::vector<double> errors);
double median(std::vector<double> values);

struct MeasurementNoiseEstimate {
  std::int64_t count = 0;
  double range_bias_m = 0.0, bearing_bias_rad = 0.0;     // medians of the residuals
  double sigma_range_m = 0.0, sigma_bearing_rad = 0.0;   // 1.4826 * MAD
  double outlier_fraction = 0.0;                          // residual beyond 5 sigma in range or bearing
};

// Residuals z - h(truth pose, truth landmark) of every measurement whose step has a truth pose and whose
// truth id names a truth landmark. dof_scale multiplies the sigmas: use sqrt(n / (n - p)) when the truth
// poses were themselves fitted to the same measurements (p parameters per n residuals).
MeasurementNoiseEstimate estimate_measurement_noise(const Scenario& scenario, double dof_scale = 1.0);

struct MotionNoiseEstimate {
  std::int64_t windows = 0;
  double sigma_u1 = 0.0;  // speed noise: m/s for the velocity and Ackermann models
  double sigma_u2 = 0.0;  // omega (rad/s, velocity model) or steering (rad, Ackermann)
};

// Replays the noise-free motion model from each truth pose over a window of about window_s to the next truth
// pose, and compares. The engine adds noise of covariance Q_u to every step's control, so the predicted
// pose covariance over the window is P = sigma_1^2 A + sigma_2^2 B, with A and B propagated through the
// model's Jacobians (P <- J_x P J_x^T + J_u diag(1, 0, 0) J_u^T, resp. diag(0, 1, 0)). For a Gaussian error
// e of variance s^2, median(e^2) = 0.4549 s^2, hence the robust fits
//   sigma_1^2 = median(e_along^2 / A_along) / 0.4549     (along-track error: mostly the speed)
//   sigma_2^2 = median(e_theta^2 / B_theta) / 0.4549     (heading error: the turn rate or the steering)
// over windows in which the robot moves (mean speed above min_speed). The cross terms (speed noise turning
// the heading of the Ackermann model) are ignored: they are small at the speeds of these datasets.
MotionNoiseEstimate estimate_motion_noise(const Scenario& scenario, double window_s = 1.0, double min_speed = 0.05);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_
