// Noise models estimated from ground truth (DESIGN.md §6; the values are tuning inputs, not dataset facts).
// Two figures for every sigma: 1.4826 * MAD (the median absolute deviation, which equals the standard deviation
// for Gaussian errors and ignores the tails), and the standard deviation after removing gross outliers (beyond
// 5 sigma), which keeps the heavy but real tails that a filter must be told about. The second is the default.
#ifndef ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_
#define ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_

#include <cstdint>
#include <vector>

#include "core/types/scenario.h"

namespace arbor {

// 1.4826 * median(|e - median(e)|); 0 for an empty input.
double robust_sigma(std::vector<double> errors);

struct MeasurementNoiseEstimate {
  std::int64_t count = 0;
  double range_bias_m = 0.0, bearing_bias_rad = 0.0;     // medians of the residuals
  double sigma_range_m = 0.0, sigma_bearing_rad = 0.0;   // standard deviation within 5 sigma
  double mad_sigma_range_m = 0.0, mad_sigma_bearing_rad = 0.0;  // 1.4826 * MAD
  double outlier_fraction = 0.0;                          // residual beyond 5 sigma in range or bearing
  double beyond_3sigma_fraction = 0.0;                    // beyond 3 sigma (0.5 % for Gaussian residuals)
};

// The standard deviation about center of the residuals within 5 sigma, starting from sigma = robust.
double tail_respecting_sigma(const std::vector<double>& e, double center, double robust);

// Residuals z - h(truth pose, truth landmark) of every measurement whose step has a truth pose and whose
// truth id names a truth landmark. dof_scale multiplies the sigmas: use sqrt(n / (n - p)) when the truth
// poses were themselves fitted to the same measurements (p parameters per n residuals).
MeasurementNoiseEstimate estimate_measurement_noise(const Scenario& scenario, double dof_scale = 1.0);

struct MotionNoiseEstimate {
  std::int64_t windows = 0;
  // Continuous-time densities of the two noise sources: speed q_v [m^2/s], and turn rate q_omega [rad^2/s]
  // (velocity, odometry) or steering q_steer [rad^2 s] (Ackermann). q: mean within 5 sigma; mad_q: median-based.
  double q_1 = 0.0, q_2 = 0.0;
  double mad_q_1 = 0.0, mad_q_2 = 0.0;
};

// Replays the noise-free motion model from each truth pose over a window of about window_s to the next truth
// pose, and compares. With white noise of density q on one source, the window's predicted covariance is
// q A, A propagated by the model's own prediction with unit density (P <- G P G^T + Q_d(q = 1)). For a
// Gaussian error e of variance s^2, e^2 / A is q times a chi-square(1), hence
//   q_1 = E[e_along^2 / A_along]     (along-track error: mostly the speed)
//   q_2 = E[e_theta^2 / B_theta]     (heading error: the turn rate or the steering)
// over windows in which the robot moves (mean speed above min_speed), the expectation taken over ratios within
// 5 sigma (and, as the MAD figure, as median / 0.4549). The cross terms (speed noise turning the heading of
// the Ackermann model) are ignored: they are small at the speeds of these datasets. The motion-proportional
// densities (k_*) are left at zero: a rate density is what a short window can tell.
MotionNoiseEstimate estimate_motion_noise(const Scenario& scenario, double window_s = 1.0, double min_speed = 0.05);

// What `convert --estimate-noise` does with the estimates of a velocity-model dataset (UTIAS): each replaces
// the scenario's documented default where it rests on data (a count or window above zero).
void apply_noise_estimates(const MeasurementNoiseEstimate& measurement, const MotionNoiseEstimate& motion,
                           Scenario* scenario);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_NOISE_ESTIMATION_H_
