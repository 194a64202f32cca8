// The motion model a scenario names, behind one small value type the engine can call per particle.
// Every model is a noise-free propagation plus the covariance its continuous-time noise adds over the
// control's interval; the engine accumulates both between scans and samples once per scan.
#ifndef ARBOR_CORE_MODELS_MOTION_MODEL_H_
#define ARBOR_CORE_MODELS_MOTION_MODEL_H_

#include <string>

#include "core/enum_names.h"
#include "core/models/ackermann_model.h"
#include "core/models/odometry_model.h"
#include "core/models/velocity_model.h"

namespace arbor {

enum class MotionModelKind { kOdometry, kVelocity, kAckermann };

// As scenario files and the command line name them (core/enum_names.h).
template <> inline constexpr EnumNames<MotionModelKind, 3> kNamesOf<MotionModelKind>{
    {{MotionModelKind::kOdometry, "odometry"}, {MotionModelKind::kVelocity, "velocity"},
     {MotionModelKind::kAckermann, "ackermann"}}};

struct MotionModel {
  MotionModelKind kind = MotionModelKind::kOdometry;
  OdometryNoise odometry;
  VelocityNoise velocity;
  AckermannNoise ackermann;
  AckermannVehicle vehicle;

  // Noise-free propagation of pose x by control u, with optional Jacobian d x'/d x.
  Pose2 apply(const Pose2& x, const Vec3& u, Mat3* J_pose = nullptr) const {
    switch (kind) {
      case MotionModelKind::kOdometry: return odometry_apply(x, u, J_pose, nullptr);
      case MotionModelKind::kVelocity: return velocity_apply(x, u, J_pose, nullptr);
      case MotionModelKind::kAckermann: return ackermann_apply(x, u, vehicle, J_pose);
    }
    return x;
  }
  // Covariance that the control adds to an exact start pose x over its interval, from the continuous-time
  // noise (core/models/twist_motion.h). dt is the step's duration: the velocity and Ackermann controls carry
  // their own (u[2]); the odometry reading does not.
  Mat3 process_noise(const Pose2& x, const Vec3& u, double dt) const { return body_noise(u, dt).at(x.theta); }
  // The same in the start pose's frame: it does not depend on the pose, so it can be shared by all particles.
  BodyProcessNoise body_noise(const Vec3& u, double dt) const {
    switch (kind) {
      case MotionModelKind::kOdometry: return odometry_body_noise(u, dt, odometry);
      case MotionModelKind::kVelocity: return velocity_body_noise(u, velocity);
      case MotionModelKind::kAckermann: return ackermann_body_noise(u, vehicle, ackermann);
    }
    return {};
  }
  // EKF prediction through one control (Probabilistic Robotics Table 3.3, line 3): x <- g(x, u) and
  // P <- G_x P G_x^T + Q_d.
  void predict(Pose2* x, Mat3* P, const Vec3& u, double dt) const { predict(x, P, u, body_noise(u, dt)); }
  void predict(Pose2* x, Mat3* P, const Vec3& u, const BodyProcessNoise& noise) const {
    const Mat3 Q = noise.at(x->theta);
    Mat3 G = Mat3::Identity();
    *x = apply(*x, u, &G);
    *P = G * *P * G.transpose() + Q;
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_MOTION_MODEL_H_
