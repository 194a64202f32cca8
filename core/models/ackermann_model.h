// Ackermann (car-like) model u = (v_e, alpha, dt) for the ACFR ute of Victoria Park and the Car Park: the
// encoder sits on the rear-left wheel and the state is the LASER's pose, which is ahead of the rear axle.
// Equations: Guivant & Nebot 2001; facts in data/victoria_park/SOURCE.md.
#ifndef ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_
#define ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_

#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

struct AckermannVehicle {
  double wheelbase_m = 2.83;        // L
  double encoder_offset_m = 0.76;   // H: rear-left wheel encoder from the axle centre
  double laser_forward_m = 3.78;    // a: laser ahead of the rear axle (L + 0.95)
  double laser_left_m = 0.50;       // b
};

struct AckermannNoise {
  double sigma_v_mps = 0.7;                     // speed (ACFR reference filter's tuning)
  double sigma_steer_rad = 7.0 * M_PI / 180.0;  // steering
};

// v_c = v_e / (1 - tan(alpha) H / L) converts the wheel speed to the axle centre; with k = v_c tan(alpha) / L:
//   x'   = x + dt (v_c cos(phi) - k (a sin(phi) + b cos(phi)))
//   y'   = y + dt (v_c sin(phi) + k (a cos(phi) - b sin(phi)))
//   phi' = phi + dt k
inline Pose2 ackermann_apply(const Pose2& x, const Vec3& u, const AckermannVehicle& car, Mat3* J_pose, Mat3* J_u) {
  const double v_e = u[0], alpha = u[1], dt = u[2];
  const double L = car.wheelbase_m, H = car.encoder_offset_m, a = car.laser_forward_m, b = car.laser_left_m;
  const double T = std::tan(alpha), sec2 = 1.0 + T * T;
  const double D = 1.0 - T * H / L;
  const double v_c = v_e / D;
  const double k = v_c * T / L;
  const double c = std::cos(x.theta), s = std::sin(x.theta);
  const double px = a * s + b * c, py = a * c - b * s;
  const double vx = v_c * c - k * px, vy = v_c * s + k * py;
  if (J_pose) *J_pose << 1, 0, dt * (-v_c * s - k * py), 0, 1, dt * (v_c * c - k * px), 0, 0, 1;
  if (J_u) {
    const double dvc_dve = 1.0 / D, dvc_dalpha = v_e * (H / L) * sec2 / (D * D);
    const double dk_dve = dvc_dve * T / L, dk_dalpha = (dvc_dalpha * T + v_c * sec2) / L;
    *J_u << dt * (c * dvc_dve - px * dk_dve), dt * (c * dvc_dalpha - px * dk_dalpha), vx,  //
        dt * (s * dvc_dve + py * dk_dve), dt * (s * dvc_dalpha + py * dk_dalpha), vy,      //
        dt * dk_dve, dt * dk_dalpha, k;
  }
  return {x.x + dt * vx, x.y + dt * vy, wrap_angle(x.theta + dt * k)};
}

inline Mat3 ackermann_control_covariance(const AckermannNoise& n) {
  return Vec3(n.sigma_v_mps * n.sigma_v_mps, n.sigma_steer_rad * n.sigma_steer_rad, 0.0).asDiagonal();
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_
