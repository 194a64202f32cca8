// Closed-form 2D rigid alignment: the pose world_T_robot that best maps points measured in the robot frame
// onto their paired map points in the least-squares sense (Umeyama 1991 without scale, specialised to SE(2)).
#ifndef ARBOR_VARIANTS_ASSOCIATION_RIGID_ALIGNMENT_H_
#define ARBOR_VARIANTS_ASSOCIATION_RIGID_ALIGNMENT_H_

#include <cmath>
#include <span>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor::association {

// Minimises sum |R(theta) p_i + t - q_i|^2 over (t, theta). With centred points p', q' the optimum is
//   theta = atan2(sum p'_x q'_y - p'_y q'_x, sum p'_x q'_x + p'_y q'_y),  t = q_mean - R(theta) p_mean.
// Needs at least two distinct points for theta to be determined; false otherwise.
inline bool align_rigid_2d(std::span<const Vec2> p_robot, std::span<const Vec2> q_world, Pose2* world_T_robot) {
  const std::size_t k = p_robot.size();
  if (k < 2 || q_world.size() != k) return false;
  Vec2 p_mean = Vec2::Zero(), q_mean = Vec2::Zero();
  for (std::size_t i = 0; i < k; ++i) {
    p_mean += p_robot[i];
    q_mean += q_world[i];
  }
  p_mean /= static_cast<double>(k);
  q_mean /= static_cast<double>(k);
  double sin_sum = 0.0, cos_sum = 0.0;
  for (std::size_t i = 0; i < k; ++i) {
    const Vec2 a = p_robot[i] - p_mean, b = q_world[i] - q_mean;
    sin_sum += a.x() * b.y() - a.y() * b.x();
    cos_sum += a.x() * b.x() + a.y() * b.y();
  }
  if (sin_sum == 0.0 && cos_sum == 0.0) return false;
  const double theta = std::atan2(sin_sum, cos_sum);
  const double c = std::cos(theta), s = std::sin(theta);
  world_T_robot->x = q_mean.x() - (c * p_mean.x() - s * p_mean.y());
  world_T_robot->y = q_mean.y() - (s * p_mean.x() + c * p_mean.y());
  world_T_robot->theta = theta;
  return true;
}

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_RIGID_ALIGNMENT_H_
