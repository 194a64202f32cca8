// Range-bearing measurement z = (r, phi) of a point landmark m from pose x (Probabilistic Robotics §6.6):
//   r = |m - p|,  phi = atan2(m_y - y, m_x - x) - theta  (wrapped).
// Jacobians wrt the landmark (EKF update, JCBB) and wrt the pose (FastSLAM 2.0 proposal, JCBB with a pose
// covariance), and the inverse model that initialises a landmark from its first measurement.
#ifndef ARBOR_CORE_MODELS_RANGE_BEARING_MODEL_H_
#define ARBOR_CORE_MODELS_RANGE_BEARING_MODEL_H_

#include <algorithm>
#include <cmath>

#include "core/math/angles.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

// A landmark at the sensor itself has no bearing; q is floored so values and Jacobians stay finite there.
inline constexpr double kMinSquaredRange = 1e-12;

// The predicted range alone, to the bit what range_bearing_predict gives: a landmark can be ruled out of view
// by its range before the bearing's atan2 and the Jacobians are paid for.
inline double predicted_range(const Pose2& x, const Vec2& m) {
  const double dx = m.x() - x.x, dy = m.y() - x.y;
  return std::sqrt(std::max(dx * dx + dy * dy, kMinSquaredRange));
}

// The Jacobians alone, to the bit what range_bearing_predict gives: a caller that has the prediction (and has
// kept the landmark in view by it) pays only for these.
inline void range_bearing_jacobians(const Pose2& x, const Vec2& m, Mat2* J_z_lm, Mat23* J_z_pose) {
  const double dx = m.x() - x.x, dy = m.y() - x.y;
  const double q = std::max(dx * dx + dy * dy, kMinSquaredRange);
  const double r = std::sqrt(q);
  if (J_z_lm) *J_z_lm << dx / r, dy / r, -dy / q, dx / q;
  if (J_z_pose) *J_z_pose << -dx / r, -dy / r, 0, dy / q, -dx / q, -1;
}

inline Vec2 range_bearing_predict(const Pose2& x, const Vec2& m, Mat2* J_z_lm = nullptr, Mat23* J_z_pose = nullptr) {
  const double dx = m.x() - x.x, dy = m.y() - x.y;
  const double q = std::max(dx * dx + dy * dy, kMinSquaredRange);
  const double r = std::sqrt(q);
  range_bearing_jacobians(x, m, J_z_lm, J_z_pose);
  return {r, wrap_angle(std::atan2(dy, dx) - x.theta)};
}

// Innovation z - z_hat with the bearing difference wrapped.
inline Vec2 range_bearing_innovation(const Vec2& z, const Vec2& z_hat) {
  return {z.x() - z_hat.x(), wrap_angle(z.y() - z_hat.y())};
}

// m = p + r (cos(theta + phi), sin(theta + phi)), with d m / d z.
inline Vec2 range_bearing_inverse(const Pose2& x, const Vec2& z, Mat2* J_lm_z = nullptr) {
  const double angle = x.theta + z.y();
  const double c = std::cos(angle), s = std::sin(angle);
  if (J_lm_z) *J_lm_z << c, -z.x() * s, s, z.x() * c;
  return {x.x + z.x() * c, x.y + z.x() * s};
}

// Covariance of a landmark initialised from one measurement with noise R: J R J^T, J = d m / d z.
inline Mat2 range_bearing_initial_covariance(const Pose2& x, const Vec2& z, const Mat2& R) {
  Mat2 J;
  range_bearing_inverse(x, z, &J);
  Mat2 cov = J * R * J.transpose();
  return 0.5 * (cov + cov.transpose());
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_RANGE_BEARING_MODEL_H_
