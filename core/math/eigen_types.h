// Fixed-size Eigen aliases used throughout Arbor (in the manner of Ceres's EigenTypes).
#ifndef ARBOR_CORE_MATH_EIGEN_TYPES_H_
#define ARBOR_CORE_MATH_EIGEN_TYPES_H_

#include <Eigen/Core>

namespace arbor {
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat2 = Eigen::Matrix2d;
using Mat3 = Eigen::Matrix3d;
using Mat23 = Eigen::Matrix<double, 2, 3>;
using Mat32 = Eigen::Matrix<double, 3, 2>;
}  // namespace arbor

#endif  // ARBOR_CORE_MATH_EIGEN_TYPES_H_
