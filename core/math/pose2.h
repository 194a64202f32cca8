// A pose in SE(2): position in metres and heading in radians, heading kept in (-pi, pi].
#ifndef ARBOR_CORE_MATH_POSE2_H_
#define ARBOR_CORE_MATH_POSE2_H_

#include <cmath>

#include "core/math/angles.h"
#include "core/math/eigen_types.h"

namespace arbor {

struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double theta = 0.0;

  Vec2 position() const { return {x, y}; }
  Vec3 vector() const { return {x, y, theta}; }
  static Pose2 from_vector(const Vec3& v) { return {v.x(), v.y(), wrap_angle(v.z())}; }

  // world_T_b = world_T_a * a_T_b.
  Pose2 compose(const Pose2& a_T_b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * a_T_b.x - s * a_T_b.y, y + s * a_T_b.x + c * a_T_b.y, wrap_angle(theta + a_T_b.theta)};
  }
  // a_T_b = inverse(world_T_a) * world_T_b, with *this = world_T_a.
  Pose2 between(const Pose2& world_T_b) const {
    const double c = std::cos(theta), s = std::sin(theta);
    const double dx = world_T_b.x - x, dy = world_T_b.y - y;
    return {c * dx + s * dy, -s * dx + c * dy, wrap_angle(world_T_b.theta - theta)};
  }
  // p_world = world_T_robot * p_robot.
  Vec2 transform(const Vec2& p_robot) const {
    const double c = std::cos(theta), s = std::sin(theta);
    return {x + c * p_robot.x() - s * p_robot.y(), y + s * p_robot.x() + c * p_robot.y()};
  }
};

// Pose difference a - b with the heading difference wrapped: the error used by NEES and ATE.
inline Vec3 pose_error(const Pose2& a, const Pose2& b) { return {a.x - b.x, a.y - b.y, wrap_angle(a.theta - b.theta)}; }

}  // namespace arbor

#endif  // ARBOR_CORE_MATH_POSE2_H_
