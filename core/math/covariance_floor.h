// Keeps a 2x2 landmark covariance positive definite in floating point.
#ifndef ARBOR_CORE_MATH_COVARIANCE_FLOOR_H_
#define ARBOR_CORE_MATH_COVARIANCE_FLOOR_H_

#include <cmath>

#include <Eigen/Eigenvalues>

#include "core/math/eigen_types.h"

namespace arbor {

// The smallest ratio of a landmark covariance's eigenvalues that double arithmetic keeps definite: beyond it
// det = ad - b^2 of a rotated ellipse is lost to rounding. A zero-range measurement (a valid input: the
// landmark at the sensor) initialises a rank-1 covariance, since its bearing moves the point by r dphi = 0;
// the first update then made it indefinite and aborted the run. Ordinary data stays far from the floor, so
// its runs are bit-identical with and without it.
inline constexpr double kMinEigenvalueRatio = 1e-12;

// Raises the smaller eigenvalue of the symmetric cov to kMinEigenvalueRatio times the larger when it is
// below (the regularisation the EKF needs, not a change of the estimate's shape anywhere else).
inline void floor_covariance(Mat2* cov) {
  const double trace = (*cov)(0, 0) + (*cov)(1, 1);
  const double det = (*cov)(0, 0) * (*cov)(1, 1) - (*cov)(0, 1) * (*cov)(1, 0);
  // det / trace^2 = l1 l2 / (l1 + l2)^2 > ratio / (1 + ratio)^2 exactly when l_min / l_max > ratio.
  if (det > kMinEigenvalueRatio * trace * trace) return;
  Eigen::SelfAdjointEigenSolver<Mat2> eigen(*cov);
  Vec2 values = eigen.eigenvalues();  // ascending
  values(0) = std::max(values(0), kMinEigenvalueRatio * values(1));
  *cov = eigen.eigenvectors() * values.asDiagonal() * eigen.eigenvectors().transpose();
  *cov = 0.5 * (*cov + cov->transpose());
}

}  // namespace arbor

#endif  // ARBOR_CORE_MATH_COVARIANCE_FLOOR_H_
