// Ackermann (car-like) model u = (v_e, alpha, dt) for the ACFR ute of Victoria Park and the Car Park: the
// encoder sits on the rear-left wheel and the state is the LASER's pose, which is ahead of the rear axle.
// Equations: Guivant & Nebot 2001; facts in data/victoria_park/SOURCE.md.
#ifndef ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_
#define ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_

#include <cmath>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/twist_motion.h"

namespace arbor {

struct AckermannVehicle {
  double wheelbase_m = 2.83;        // L
  double encoder_offset_m = 0.76;   // H: rear-left wheel encoder from the axle centre
  double laser_forward_m = 3.78;    // a: laser ahead of the rear axle (L + 0.95)
  double laser_left_m = 0.50;       // b
};

// White noise on the wheel speed and on the steering angle, as power spectral densities: over an interval
// of T seconds the speed error integrates to a distance variance q_v T and the steering error to a heading
// variance (v tan'(alpha) / L)^2 q_steer T. (For a per-reading sigma at a reading period dt0 the equivalent
// density is sigma^2 dt0.)
struct AckermannNoise {
  double q_v = 0.01;        // m^2/s
  double q_steer = 2.5e-5;  // rad^2 s
};

// D = 1 - tan(alpha) H / L, by which the encoder's speed is divided to give the axle centre's; at D = 0 the
// model has no answer (the scenario reader bounds it away from 0).
inline double encoder_to_axle_divisor(double tan_alpha, const AckermannVehicle& car) {
  return 1.0 - tan_alpha * car.encoder_offset_m / car.wheelbase_m;
}

// The laser's body-frame twist for a control, and d twist / d (v_e, alpha). With v_c = v_e / (1 - tan(alpha)
// H / L) the axle-centre speed and k = v_c tan(alpha) / L the turn rate, the laser at (a, b) from the axle
// centre moves with (v_c - k b, k a) and turns at k.
inline Twist ackermann_twist(const Vec3& u, const AckermannVehicle& car, Mat32* d_twist = nullptr) {
  const double v_e = u[0], alpha = u[1];
  const double L = car.wheelbase_m, H = car.encoder_offset_m, a = car.laser_forward_m, b = car.laser_left_m;
  const double T = std::tan(alpha), sec2 = 1.0 + T * T;
  const double D = encoder_to_axle_divisor(T, car);
  const double v_c = v_e / D;
  const double k = v_c * T / L;
  if (d_twist) {
    const double dvc_dve = 1.0 / D, dvc_dalpha = v_e * (H / L) * sec2 / (D * D);
    const double dk_dve = dvc_dve * T / L, dk_dalpha = (dvc_dalpha * T + v_c * sec2) / L;
    *d_twist << dvc_dve - b * dk_dve, dvc_dalpha - b * dk_dalpha,  //
        a * dk_dve, a * dk_dalpha,                                  //
        dk_dve, dk_dalpha;
  }
  return {v_c - k * b, k * a, k};
}

// The laser's exact end pose after dt = u[2] of constant (v_e, alpha) (Guivant & Nebot 2001 integrate the
// same velocities with an Euler step; the arc agrees to O(dt^2) and does not change when a reading is split).
inline Pose2 ackermann_apply(const Pose2& x, const Vec3& u, const AckermannVehicle& car, Mat3* J_pose) {
  return apply_twist(x, ackermann_twist(u, car), u[2], J_pose);
}

inline BodyProcessNoise ackermann_body_noise(const Vec3& u, const AckermannVehicle& car, const AckermannNoise& n) {
  Mat32 B;
  const Twist xi = ackermann_twist(u, car, &B);
  return {twist_body_noise(xi, u[2], B, Vec2(n.q_v, n.q_steer).asDiagonal()), 0.0};
}

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_ACKERMANN_MODEL_H_
