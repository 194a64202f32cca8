// The range-bearing sensor: its reach, field of view and noise (the measurement function itself is in
// range_bearing_model.h).
#ifndef ARBOR_CORE_MODELS_SENSOR_MODEL_H_
#define ARBOR_CORE_MODELS_SENSOR_MODEL_H_

#include <cmath>
#include <limits>

#include "core/math/angles.h"
#include "core/math/eigen_types.h"

namespace arbor {

struct SensorModel {
  double max_range_m = 30.0;
  double min_range_m = 0.0;
  double fov_rad = 2.0 * kPi;  // full field of view, centred on the heading
  double sigma_range_m = 0.1;
  double sigma_bearing_rad = 0.01;
  double sigma_signature = std::numeric_limits<double>::quiet_NaN();  // NaN: signatures not used
  Mat2 R() const { return Vec2(sigma_range_m * sigma_range_m, sigma_bearing_rad * sigma_bearing_rad).asDiagonal(); }
  bool in_view(const Vec2& z) const {
    return z.x() <= max_range_m && z.x() >= min_range_m && std::abs(z.y()) <= 0.5 * fov_rad;
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_SENSOR_MODEL_H_
