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

// The landmark's offset from the pose and its squared and plain range, computed one way for the prediction,
// the range alone and the Jacobians, so that each gives to the bit what the others do.
struct RangeGeometry {
  double dx, dy, q, r;
};
inline RangeGeometry range_geometry(const Pose2& x, const Vec2& m) {
  const double dx = m.x() - x.x, dy = m.y() - x.y;
  const double q = std::max(dx * dx + dy * dy, kMinSquaredRange);
  return {dx, dy, q, std::sqrt(q)};
}

// The predicted range alone: a landmark can be ruled out of view by its range before the bearing's atan2 and
// the Jacobians are paid for.
inline double predicted_range(const Pose2& x, const Vec2& m) { return range_geometry(x, m).r; }

// The Jacobians of a geometry already computed.
inline void range_bearing_jacobians(const RangeGeometry& g, Mat2* J_z_lm, Mat23* J_z_pose) {
  if (J_z_lm) *J_z_lm << g.dx / g.r, g.dy / g.r, -g.dy / g.q, g.dx / g.q;
  if (J_z_pose) *J_z_pose << -g.dx / g.r, -g.dy / g.r, 0, g.dy / g.q, -g.dx / g.q, -1;
}
// The Jacobians alone: a caller that has the prediction (and has kept the landmark in view by it) pays only
// for these.
inline void range_bearing_jacobians(const Pose2& x, const Vec2& m, Mat2* J_z_lm, Mat23* J_z_pose) {
  range_bearing_jacobians(range_geometry(x, m), J_z_lm, J_z_pose);
}

inline Vec2 range_bearing_predict(const Pose2& x, const Vec2& m, Mat2* J_z_lm = nullptr, Mat23* J_z_pose = nullptr) {
  const RangeGeometry g = range_geometry(x, m);
  range_bearing_jacobians(g, J_z_lm, J_z_pose);
  return {g.r, wrap_angle(std::atan2(g.dy, g.dx) - x.theta)};
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
