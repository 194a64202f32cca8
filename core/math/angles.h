// Angle wrapping: every angle Arbor stores or differences lies in (-pi, pi].
#ifndef ARBOR_CORE_MATH_ANGLES_H_
#define ARBOR_CORE_MATH_ANGLES_H_

#include <cmath>
#include <numbers>

namespace arbor {

inline constexpr double kPi = std::numbers::pi;

// Wraps to (-pi, pi]. Exact for inputs already in range, so wrapping twice changes nothing.
inline double wrap_angle(double angle_rad) {
  if (angle_rad > -kPi && angle_rad <= kPi) return angle_rad;
  double wrapped = std::remainder(angle_rad, 2.0 * kPi);  // in [-pi, pi]
  if (wrapped <= -kPi) wrapped += 2.0 * kPi;
  return wrapped;
}

}  // namespace arbor

#endif  // ARBOR_CORE_MATH_ANGLES_H_
