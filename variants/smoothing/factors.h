// Ceres residual functors for the factors of factor_graph.h, templated on the scalar for automatic
// differentiation (in the manner of Ceres's examples/slam/pose_graph_2d/pose_graph_2d_error_term.h).
// Each residual is whitened, r = W e with W^T W = Sigma^-1, so the cost is half the Mahalanobis distance.
// Include from variants/smoothing/*.cc only: this header pulls in Ceres.
#ifndef ARBOR_VARIANTS_SMOOTHING_FACTORS_H_
#define ARBOR_VARIANTS_SMOOTHING_FACTORS_H_

#include <cmath>

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/Core>
#include <ceres/autodiff_cost_function.h>
#include <ceres/jet.h>

#include "core/check.h"
#include "core/math/angles.h"
#include "core/models/range_bearing_model.h"
#include "variants/smoothing/factor_graph.h"

namespace arbor::internal {

// Wraps to [-pi, pi) for doubles and Jets alike (the derivative of a wrap is 1, and floor's is 0).
template <typename T>
T wrap_angle_t(const T& angle) {
  using std::floor;
  constexpr double kTwoPi = 2.0 * kPi;
  return angle - kTwoPi * floor((angle + kPi) / kTwoPi);
}

// W = L^T where Sigma^-1 = L L^T (upper triangular, so the whitened residual stays cheap).
template <int N>
Eigen::Matrix<double, N, N> square_root_information(const Eigen::Matrix<double, N, N>& covariance) {
  const Eigen::Matrix<double, N, N> information = covariance.inverse();
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(0.5 * (information + information.transpose()));
  ARBOR_CHECK(llt.info() == Eigen::Success, "factor covariance is not positive definite");
  return llt.matrixL().transpose();
}

// What every factor shares: its measurement, the square root W of its information (W^T W = Sigma^-1, so the
// squared residual is the Mahalanobis distance), the whitening W e, and create(). A factor writes only its
// residual e, as operator()(parameter blocks..., residual) over Ceres' Jet types. N: residual size;
// Blocks: the sizes of its parameter blocks.
template <class Derived, int N, class Measured, int... Blocks>
class WhitenedFactor {
 public:
  WhitenedFactor(const Measured& measured, const Eigen::Matrix<double, N, N>& covariance)
      : measured_(measured), sqrt_information_(square_root_information<N>(covariance)) {}

  static ceres::CostFunction* create(const Measured& measured, const Eigen::Matrix<double, N, N>& covariance) {
    return new ceres::AutoDiffCostFunction<Derived, N, Blocks...>(new Derived(measured, covariance));
  }

 protected:
  template <typename T>
  bool whiten(const Eigen::Matrix<T, N, 1>& e, T* residual) const {
    Eigen::Map<Eigen::Matrix<T, N, 1>> r(residual);
    r = sqrt_information_.template cast<T>() * e;
    return true;
  }

  Measured measured_;

 private:
  Eigen::Matrix<double, N, N> sqrt_information_;
};

// BetweenFactor: parameters pose_from[3], pose_to[3]; residual 3; the measurement is the relative motion.
class BetweenError : public WhitenedFactor<BetweenError, 3, Pose2, 3, 3> {
 public:
  using WhitenedFactor::WhitenedFactor;

  template <typename T>
  bool operator()(const T* from, const T* to, T* residual) const {
    using std::cos;
    using std::sin;
    const Pose2& delta = measured_;
    const T c = cos(from[2]), s = sin(from[2]);
    const T dx = to[0] - from[0], dy = to[1] - from[1];
    // from^-1 * to, minus delta's translation, then rotated into delta's frame.
    const T tx = c * dx + s * dy - delta.x, ty = -s * dx + c * dy - delta.y;
    const double cd = std::cos(delta.theta), sd = std::sin(delta.theta);
    Eigen::Matrix<T, 3, 1> e;
    e << cd * tx + sd * ty, -sd * tx + cd * ty, wrap_angle_t(to[2] - from[2] - T(delta.theta));
    return whiten(e, residual);
  }
};

// A factor between a pose[3] and a landmark[2] with a 2-vector measurement: the base hands the sensor model
// the landmark's offset d = m - p in the world frame, and the model returns its error e(pose, d).
template <class Derived>
class PoseLandmarkFactor : public WhitenedFactor<Derived, 2, Vec2, 3, 2> {
 public:
  using WhitenedFactor<Derived, 2, Vec2, 3, 2>::WhitenedFactor;

  template <typename T>
  bool operator()(const T* pose, const T* landmark, T* residual) const {
    const Eigen::Matrix<T, 2, 1> d(landmark[0] - pose[0], landmark[1] - pose[1]);
    return this->whiten(static_cast<const Derived&>(*this).error(pose, d, this->measured_), residual);
  }
};

// RangeBearingFactor: z = (range, bearing); the bearing error is wrapped.
class RangeBearingError : public PoseLandmarkFactor<RangeBearingError> {
 public:
  using PoseLandmarkFactor::PoseLandmarkFactor;

  template <typename T>
  static Eigen::Matrix<T, 2, 1> error(const T* pose, const Eigen::Matrix<T, 2, 1>& d, const Vec2& z) {
    using std::atan2;
    using std::sqrt;
    const T q = d.x() * d.x() + d.y() * d.y();
    // At the sensor itself (a zero-range measurement starts its landmark there) the bearing and its
    // derivative (0/0) are undefined, and one NaN Jacobian failed the whole solve: the factor holds the
    // floored range alone there, as range_bearing_predict does for the filter.
    if (q < T(kMinSquaredRange)) return {sqrt(T(kMinSquaredRange)) - z.x(), T(0.0)};
    return {sqrt(q) - z.x(), wrap_angle_t(atan2(d.y(), d.x()) - pose[2] - z.y())};
  }
};

// PointFactor: the landmark's position in the robot frame, R(th)^T (m - p), against p_robot.
class PointError : public PoseLandmarkFactor<PointError> {
 public:
  using PoseLandmarkFactor::PoseLandmarkFactor;

  template <typename T>
  static Eigen::Matrix<T, 2, 1> error(const T* pose, const Eigen::Matrix<T, 2, 1>& d, const Vec2& p_robot) {
    using std::cos;
    using std::sin;
    const T c = cos(pose[2]), s = sin(pose[2]);
    return {c * d.x() + s * d.y() - p_robot.x(), -s * d.x() + c * d.y() - p_robot.y()};
  }
};

// PosePriorFactor: parameters pose[3]; residual 3; the measurement is the prior mean.
class PosePriorError : public WhitenedFactor<PosePriorError, 3, Pose2, 3> {
 public:
  using WhitenedFactor::WhitenedFactor;

  template <typename T>
  bool operator()(const T* pose, T* residual) const {
    const Pose2& mean = measured_;
    Eigen::Matrix<T, 3, 1> e;
    e << pose[0] - mean.x, pose[1] - mean.y, wrap_angle_t(pose[2] - T(mean.theta));
    return whiten(e, residual);
  }
};

// The cost function of each factor of the graph.
inline ceres::CostFunction* cost_of(const BetweenFactor& f) { return BetweenError::create(f.delta, f.covariance); }
inline ceres::CostFunction* cost_of(const RangeBearingFactor& f) { return RangeBearingError::create(f.z, f.covariance); }
inline ceres::CostFunction* cost_of(const PointFactor& f) { return PointError::create(f.p_robot, f.covariance); }
inline ceres::CostFunction* cost_of(const PosePriorFactor& f) { return PosePriorError::create(f.mean, f.covariance); }

}  // namespace arbor::internal

#endif  // ARBOR_VARIANTS_SMOOTHING_FACTORS_H_
