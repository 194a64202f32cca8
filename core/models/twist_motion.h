// Continuous-time motion noise shared by every motion model (DESIGN.md §2). Over one control interval the
// robot's reference point moves with a constant body-frame twist xi = (v_x, v_y, omega); the controls are
// corrupted by white noise n(t) of power spectral density Q_c, entering the twist as B n. The covariance the
// interval adds to the pose is the integral of the linearised error dynamics (Maybeck 1979, §4.9; Barfoot,
// State Estimation for Robotics, §6.2.3):
//   Q_d = int_0^T Phi(s) B Q_c B^T Phi(s)^T ds,
//   Phi(s) [d_v; d_omega] = [R(theta(s)) d_v + J (p(T) - p(s)) d_omega; d_omega],   J = [0 -1; 1 0],
// i.e. a twist error at time s shifts the rest of the path (velocity) or turns it about p(s) (turn rate).
// Because Q_d is an integral over time, an interval cut into pieces gets the same covariance (the pieces'
// Q_d propagated through each other's Jacobians add up to it): noise depends on duration and motion, not on
// how many readings cut the interval.
#ifndef ARBOR_CORE_MODELS_TWIST_MOTION_H_
#define ARBOR_CORE_MODELS_TWIST_MOTION_H_

#include <algorithm>
#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

struct Twist {
  double v_x = 0.0, v_y = 0.0, omega = 0.0;  // m/s, m/s, rad/s in the body frame
};

// Displacement after time t of a constant twist, in the start frame: int_0^t R(omega s) (v_x, v_y) ds.
inline Vec2 twist_displacement(const Twist& xi, double t) {
  const double a = xi.omega * t;
  double f, g;  // f = sin(a)/omega, g = (1 - cos(a))/omega, by series near omega = 0 (relative error O(a^4))
  if (std::abs(a) > 1e-4) {
    f = std::sin(a) / xi.omega;
    g = (1.0 - std::cos(a)) / xi.omega;
  } else {
    f = t * (1.0 - a * a / 6.0);
    g = t * (a / 2.0 - a * a * a / 24.0);
  }
  return {f * xi.v_x - g * xi.v_y, g * xi.v_x + f * xi.v_y};
}

// x' = x (+) exp(T xi): the exact end pose of a constant twist, with d x'/d x.
inline Pose2 apply_twist(const Pose2& x, const Twist& xi, double T, Mat3* J_pose) {
  const Vec2 d = twist_displacement(xi, T);
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const double dx = c * d.x() - s * d.y(), dy = s * d.x() + c * d.y();
  if (J_pose) *J_pose << 1, 0, -dy, 0, 1, dx, 0, 0, 1;
  return {x.x + dx, x.y + dy, wrap_angle(x.theta + xi.omega * T)};
}

// Q_d above, in the start frame, by Simpson's rule. The integrand is a
// trigonometric polynomial in omega s; with |omega h| <= 0.1 per panel the quadrature error is far below
// 1e-6 relative, and straight motion (a cubic in s) is integrated exactly.
inline constexpr double kFloorDensity = 1e-10;  // m^2/s and rad^2/s

// The covariance an interval adds, in the frame of its start pose turned by heading_offset. It does not depend
// on the start pose, so the engine computes it once per control and turns it into each particle's frame.
struct BodyProcessNoise {
  Mat3 body = Mat3::Zero();
  double heading_offset = 0.0;

  // In the world frame of a start pose with this heading.
  Mat3 at(double theta) const {
    const double a = theta + heading_offset, c = std::cos(a), s = std::sin(a);
    Mat3 R = Mat3::Identity();
    R.topLeftCorner<2, 2>() << c, -s, s, c;
    const Mat3 Q = R * body * R.transpose();
    return 0.5 * (Q + Q.transpose());
  }
};

inline Mat3 twist_body_noise(const Twist& xi, double T, const Mat32& B, const Mat2& Q_c) {
  if (!(T > 0.0)) return Mat3::Zero();  // no time, no noise (an odometry reading clamps its dt above 0)
  const int panels = 2 * std::clamp(static_cast<int>(std::ceil(std::abs(xi.omega * T) / 0.2)), 2, 64);
  const double h = T / panels;
  const Mat3 BQB = B * Q_c * B.transpose();
  const Vec2 end = twist_displacement(xi, T);
  Mat3 body = Mat3::Zero();  // in the start frame; rotated to the world at the end
  for (int i = 0; i <= panels; ++i) {
    const double s = i * h;
    const double a = xi.omega * s;
    const Vec2 rest = end - twist_displacement(xi, s);
    Mat3 Phi;
    Phi << std::cos(a), -std::sin(a), -rest.y(),  //
        std::sin(a), std::cos(a), rest.x(),         //
        0, 0, 1;
    const double w = (i == 0 || i == panels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    body += w * Phi * BQB * Phi.transpose();
  }
  body *= h / 3.0;
  // A floor density on every axis (lateral slip, say), so that a standing robot's prediction stays positive
  // definite; as a density it adds up over pieces like the rest.
  body.diagonal().array() += kFloorDensity * T;
  return body;
}

// White noise on the forward speed and the turn rate of a twist (velocity and odometry models):
//   PSD of the speed      q_v + k_v |v|                     [m^2/s]: q_v m^2/s, k_v m^2 per metre travelled
//   PSD of the turn rate  q_omega + k_wv |v| + k_ww |omega| [rad^2/s]: rad^2/s, rad^2 per metre, rad^2 per radian
// So over an interval the speed error integrates to variance q_v T + k_v * distance, and the heading error to
// q_omega T + k_wv * distance + k_ww * |turn|. The rate terms keep a standing robot's prediction positive
// definite and grow with time, not with the number of readings.
struct TwistNoise {
  double q_v = 0.0025, q_omega = 0.0025;
  double k_v = 0.0, k_wv = 0.0, k_ww = 0.0;

  Mat2 psd(double v, double omega) const {
    return Vec2(q_v + k_v * std::abs(v), q_omega + k_wv * std::abs(v) + k_ww * std::abs(omega)).asDiagonal();
  }
};

// B of a twist whose noise is on (forward speed, turn rate).
inline Mat32 forward_turn_noise_map() {
  Mat32 B;
  B << 1, 0, 0, 0, 0, 1;
  return B;
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_TWIST_MOTION_H_
