// Odometry motion model u = (delta_rot1, delta_trans, delta_rot2) (Thrun, Burgard & Fox, Probabilistic
// Robotics, Table 5.6, sample_motion_model_odometry): rotate, translate, rotate.
#ifndef ARBOR_CORE_MODELS_ODOMETRY_MODEL_H_
#define ARBOR_CORE_MODELS_ODOMETRY_MODEL_H_

#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

// alpha1..alpha4 as in Probabilistic Robotics Table 5.6 (variances grow with the motion), plus floors so a
// standing robot still has a positive definite prediction covariance (FastSLAM 2.0 samples from it).
struct OdometryNoise {
  double alpha1 = 0.0025, alpha2 = 0.0005, alpha3 = 0.0025, alpha4 = 0.0005;
  double min_rot_sigma_rad = 1e-4, min_trans_sigma_m = 1e-4;
};

// x' = x + trans*cos(theta + rot1), y' = y + trans*sin(theta + rot1), theta' = theta + rot1 + rot2.
inline Pose2 odometry_apply(const Pose2& x, const Vec3& u, Mat3* J_pose, Mat3* J_u) {
  const double heading = x.theta + u[0];
  const double c = std::cos(heading), s = std::sin(heading);
  if (J_pose) *J_pose << 1, 0, -u[1] * s, 0, 1, u[1] * c, 0, 0, 1;
  if (J_u) *J_u << -u[1] * s, c, 0, u[1] * c, s, 0, 1, 0, 1;
  return {x.x + u[1] * c, x.y + u[1] * s, wrap_angle(heading + u[2])};
}

inline Mat3 odometry_control_covariance(const Vec3& u, const OdometryNoise& n) {
  const double rot1 = wrap_angle(u[0]), trans = u[1], rot2 = wrap_angle(u[2]);
  const double var_rot1 = n.alpha1 * rot1 * rot1 + n.alpha2 * trans * trans + n.min_rot_sigma_rad * n.min_rot_sigma_rad;
  const double var_trans =
      n.alpha3 * trans * trans + n.alpha4 * (rot1 * rot1 + rot2 * rot2) + n.min_trans_sigma_m * n.min_trans_sigma_m;
  const double var_rot2 = n.alpha1 * rot2 * rot2 + n.alpha2 * trans * trans + n.min_rot_sigma_rad * n.min_rot_sigma_rad;
  return Vec3(var_rot1, var_trans, var_rot2).asDiagonal();
}

// The odometry control that takes pose a to pose b (inverse of odometry_apply), used by the simulator.
inline Vec3 odometry_between(const Pose2& a, const Pose2& b) {
  const double dx = b.x - a.x, dy = b.y - a.y;
  const double trans = std::hypot(dx, dy);
  const double rot1 = trans < 1e-12 ? 0.0 : wrap_angle(std::atan2(dy, dx) - a.theta);
  return {rot1, trans, wrap_angle(b.theta - a.theta - rot1)};
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_ODOMETRY_MODEL_H_
