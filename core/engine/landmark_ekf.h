// One landmark's 2x2 EKF in a FastSLAM particle (Montemerlo et al. 2002, §3.2-3.3): started from a
// measurement by the inverse measurement model, updated at a known pose. Shared by the engine's step and by
// resample-move's replay of a window, so both apply the same arithmetic.
#ifndef ARBOR_CORE_ENGINE_LANDMARK_EKF_H_
#define ARBOR_CORE_ENGINE_LANDMARK_EKF_H_

#include <Eigen/LU>

#include "core/check.h"
#include "core/engine/numerical_breakdown.h"
#include "core/engine/measurement_likelihood.h"
#include "core/math/covariance_floor.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/range_bearing_model.h"
#include "core/types/landmark.h"

namespace arbor {

class LandmarkEkf {
 public:
  // R: the measurement noise covariance.
  LandmarkEkf(const Mat2& R, const MeasurementLikelihood& likelihood) : R_(R), likelihood_(likelihood) {}

  // A landmark's first estimate from measurement z at pose (inverse measurement model).
  void start(const Pose2& pose, const Vec2& z, Vec2* mean, Mat2* cov) const {
    *mean = range_bearing_inverse(pose, z);
    *cov = range_bearing_initial_covariance(pose, z, R_);
    floor_covariance(cov);  // rank 1 at zero range
  }

  // One update at a known pose (Montemerlo 2002, eq. 8-11; Joseph form); returns the measurement's
  // log-likelihood, whose innovation covariance gains pose_drift's where a loop closure allows drift.
  double update(const Pose2& pose, const Vec2& z, LandmarkId id, Vec2* mean, Mat2* cov, const Mat3* pose_drift = nullptr) const {
    Mat2 H_m;
    Mat23 H_x;
    const Vec2 z_hat = range_bearing_predict(pose, *mean, &H_m, pose_drift ? &H_x : nullptr);
    const Vec2 nu = range_bearing_innovation(z, z_hat);
    double scale = 1.0;
    Mat2 S = H_m * *cov * H_m.transpose();
    if (pose_drift) S += H_x * *pose_drift * H_x.transpose();
    const double ll = likelihood_(nu, S + R_, &scale);
    const Mat2 R = scale * R_;
    const Mat2 Q = H_m * *cov * H_m.transpose() + R;
    const Mat2 K = *cov * H_m.transpose() * Q.inverse();
    *mean += K * nu;
    const Mat2 I_KH = Mat2::Identity() - K * H_m;
    *cov = I_KH * *cov * I_KH.transpose() + K * R * K.transpose();
    *cov = 0.5 * (*cov + cov->transpose());
    floor_covariance(cov);
    if (!((*cov)(0, 0) > 0.0 && cov->determinant() > 0.0))  // huge motion noise or controls (see the header)
      throw NumericalBreakdown(fmt::format("landmark {} covariance lost definiteness", id));
    return ll;
  }

 private:
  Mat2 R_;
  MeasurementLikelihood likelihood_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_LANDMARK_EKF_H_
