// Velocity motion model u = (v, omega, dt) (Probabilistic Robotics §5.3): a circular arc of radius v/omega,
// with the straight-line limit handled by a series expansion so values and Jacobians stay smooth at omega = 0.
#ifndef ARBOR_CORE_MODELS_VELOCITY_MODEL_H_
#define ARBOR_CORE_MODELS_VELOCITY_MODEL_H_

#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/twist_motion.h"

namespace arbor {

// White noise on the commanded v and omega (TwistNoise: densities per second, per metre and per radian).
using VelocityNoise = TwistNoise;

// In the robot frame the arc moves (v*f, v*g) with f = sin(w dt)/w, g = (1 - cos(w dt))/w.
inline Pose2 velocity_apply(const Pose2& x, const Vec3& u, Mat3* J_pose, Mat3* J_u) {
  const double v = u[0], w = u[1], dt = u[2];
  const double wdt = w * dt;
  double f, g, df_dw, dg_dw;
  if (std::abs(wdt) > 1e-4) {
    const double sw = std::sin(wdt), cw = std::cos(wdt);
    f = sw / w;
    g = (1.0 - cw) / w;
    df_dw = (dt * cw * w - sw) / (w * w);
    dg_dw = (dt * sw * w - (1.0 - cw)) / (w * w);
  } else {  // Taylor series in w; truncation error O((w dt)^4) relative.
    const double dt2 = dt * dt, dt3 = dt2 * dt, dt4 = dt3 * dt;
    f = dt - w * w * dt3 / 6.0;
    g = w * dt2 / 2.0 - w * w * w * dt4 / 24.0;
    df_dw = -w * dt3 / 3.0;
    dg_dw = dt2 / 2.0 - w * w * dt4 / 8.0;
  }
  const double df_ddt = std::cos(wdt), dg_ddt = std::sin(wdt);
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const double dx_r = v * f, dy_r = v * g;
  if (J_pose) *J_pose << 1, 0, -s * dx_r - c * dy_r, 0, 1, c * dx_r - s * dy_r, 0, 0, 1;
  if (J_u) {
    // Columns: d/dv, d/domega, d/ddt of (x', y', theta').
    *J_u << c * f - s * g, v * (c * df_dw - s * dg_dw), v * (c * df_ddt - s * dg_ddt),  //
        s * f + c * g, v * (s * df_dw + c * dg_dw), v * (s * df_ddt + c * dg_ddt),        //
        0, dt, w;
  }
  return {x.x + c * dx_r - s * dy_r, x.y + s * dx_r + c * dy_r, wrap_angle(x.theta + wdt)};
}

// Covariance the control adds to the pose over its dt = u[2] (world frame).
inline BodyProcessNoise velocity_body_noise(const Vec3& u, const VelocityNoise& n) {
  return {twist_body_noise({u[0], 0.0, u[1]}, u[2], forward_turn_noise_map(), n.psd(u[0], u[1])), 0.0};
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_VELOCITY_MODEL_H_
