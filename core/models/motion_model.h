// The motion model a scenario names, behind one small value type the engine can call per particle.
// Every model is "apply a noisy control": sampling perturbs u with its covariance Q_u and applies it
// (Probabilistic Robotics' sample_motion_model), and the Gaussian prediction is J_u Q_u J_u^T.
#ifndef ARBOR_CORE_MODELS_MOTION_MODEL_H_
#define ARBOR_CORE_MODELS_MOTION_MODEL_H_

#include <string>
#include <string_view>

#include "core/models/ackermann_model.h"
#include "core/models/odometry_model.h"
#include "core/models/velocity_model.h"

namespace arbor {

enum class MotionModelKind { kOdometry, kVelocity, kAckermann };

std::string_view to_string(MotionModelKind kind);
// Returns false for an unknown name.
bool from_string(std::string_view name, MotionModelKind* kind);

struct MotionModel {
  MotionModelKind kind = MotionModelKind::kOdometry;
  OdometryNoise odometry;
  VelocityNoise velocity;
  AckermannNoise ackermann;
  AckermannVehicle vehicle;

  // Noise-free propagation of pose x by control u, with optional Jacobians d x'/d x and d x'/d u.
  Pose2 apply(const Pose2& x, const Vec3& u, Mat3* J_pose = nullptr, Mat3* J_u = nullptr) const {
    switch (kind) {
      case MotionModelKind::kOdometry: return odometry_apply(x, u, J_pose, J_u);
      case MotionModelKind::kVelocity: return velocity_apply(x, u, J_pose, J_u);
      case MotionModelKind::kAckermann: return ackermann_apply(x, u, vehicle, J_pose, J_u);
    }
    return x;
  }
  // Q_u: covariance of the control noise, in control space (the dt component is noise-free).
  Mat3 control_covariance(const Vec3& u) const {
    switch (kind) {
      case MotionModelKind::kOdometry: return odometry_control_covariance(u, odometry);
      case MotionModelKind::kVelocity: return velocity_control_covariance(u, velocity);
      case MotionModelKind::kAckermann: return ackermann_control_covariance(ackermann);
    }
    return Mat3::Zero();
  }
  // Covariance of the predicted pose given an exact starting pose: J_u Q_u J_u^T, plus a tiny floor that
  // keeps it positive definite when the robot stands still.
  Mat3 prediction_covariance(const Pose2& x, const Vec3& u) const {
    Mat3 J_u;
    apply(x, u, nullptr, &J_u);
    Mat3 P = J_u * control_covariance(u) * J_u.transpose();
    P.diagonal().array() += 1e-12;
    return P;
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_MOTION_MODEL_H_
