// Odometry motion model u = (delta_rot1, delta_trans, delta_rot2) (Thrun, Burgard & Fox, Probabilistic
// Robotics, Table 5.6, sample_motion_model_odometry): rotate, translate, rotate.
#ifndef ARBOR_CORE_MODELS_ODOMETRY_MODEL_H_
#define ARBOR_CORE_MODELS_ODOMETRY_MODEL_H_

#include <algorithm>
#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/twist_motion.h"

namespace arbor {

// The reading (rot1, trans, rot2) is what the wheels did over the step's duration dt; for the noise it is
// taken as the constant-curvature arc with the same heading change rot1 + rot2 and the same chord (a
// differential drive read at 10-100 Hz moves on such arcs), with noise per TwistNoise. The mean is the
// rotate-translate-rotate motion itself, which is the arc's end pose when rot1 = rot2.
using OdometryNoise = TwistNoise;

// The arc of a reading: its twist over dt, and the start heading offset that makes the arc's chord point
// along theta + rot1 (zero when rot1 = rot2).
inline Twist odometry_twist(const Vec3& u, double dt, double* heading_offset) {
  const double turn = wrap_angle(u[0]) + wrap_angle(u[2]);
  const double half = 0.5 * turn;
  const double arc_per_chord = std::abs(half) > 1e-6 ? half / std::sin(half) : 1.0 + half * half / 6.0;
  *heading_offset = wrap_angle(u[0]) - half;
  return {u[1] * arc_per_chord / dt, 0.0, turn / dt};
}

// x' = x + trans*cos(theta + rot1), y' = y + trans*sin(theta + rot1), theta' = theta + rot1 + rot2.
inline Pose2 odometry_apply(const Pose2& x, const Vec3& u, Mat3* J_pose, Mat3* J_u) {
  const double heading = x.theta + u[0];
  const double c = std::cos(heading), s = std::sin(heading);
  if (J_pose) *J_pose << 1, 0, -u[1] * s, 0, 1, u[1] * c, 0, 0, 1;
  if (J_u) *J_u << -u[1] * s, c, 0, u[1] * c, s, 0, 1, 0, 1;
  return {x.x + u[1] * c, x.y + u[1] * s, wrap_angle(heading + u[2])};
}

// Covariance the reading adds to the pose (world frame), dt its duration (a floor keeps dt = 0 finite: the
// motion-proportional terms are per distance and per radian, so they stay right as dt shrinks).
inline BodyProcessNoise odometry_body_noise(const Vec3& u, double dt, const OdometryNoise& n) {
  dt = std::max(dt, 1e-9);
  BodyProcessNoise q;
  const Twist xi = odometry_twist(u, dt, &q.heading_offset);
  q.body = twist_body_noise(xi, dt, forward_turn_noise_map(), n.psd(xi.v_x, xi.omega));
  return q;
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
