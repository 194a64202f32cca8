// FastSlamOptions::gate_covariance = set: per landmark, the spread over the particle set of the measurement it
// predicts, added to each particle's innovation covariance in the association gates. By the law of total
// covariance it is what the mixture's innovation covariance adds to a particle's own.
#ifndef ARBOR_CORE_ENGINE_SET_SPREAD_H_
#define ARBOR_CORE_ENGINE_SET_SPREAD_H_

#include <unordered_map>
#include <vector>

#include "core/math/eigen_types.h"
#include "core/models/range_bearing_model.h"
#include "core/types/landmark.h"

namespace arbor {

class SetSpread {
 public:
  struct PredictedMeasurement {
    LandmarkId id;
    Vec2 z_hat;
  };

  explicit SetSpread(int particles) : predicted_(particles) {}

  // Particle i's predicted measurements of the landmarks it could see; each particle fills its own, in parallel.
  std::vector<PredictedMeasurement>& predicted(int i) { return predicted_[i]; }

  // Per landmark, the weighted covariance over the particles that hold it of their predicted measurements
  // (weights renormalised over those particles; bearings wrapped about the first particle's). Serial, in
  // particle order, so the sums are the same whatever the thread count.
  void reduce(const std::vector<double>& weights) {
    sums_.clear();
    for (std::size_t i = 0; i < predicted_.size(); ++i)
      for (const PredictedMeasurement& m : predicted_[i]) {
        auto [it, fresh] = sums_.try_emplace(m.id);
        Sum& sum = it->second;
        if (fresh) sum.reference = m.z_hat;
        const Vec2 d = range_bearing_innovation(m.z_hat, sum.reference);
        sum.w += weights[i];
        sum.first += weights[i] * d;
        sum.second += weights[i] * d * d.transpose();
      }
    for (auto& [id, sum] : sums_) {
      if (!(sum.w > 0.0)) continue;  // the spread stays zero
      const Vec2 mean = sum.first / sum.w;
      sum.spread = sum.second / sum.w - mean * mean.transpose();
      sum.spread = 0.5 * (sum.spread + sum.spread.transpose());
    }
  }

  // The spread of landmark id's predicted measurement, or null outside a scan's reduction.
  const Mat2* spread(LandmarkId id) const {
    if (sums_.empty()) return nullptr;
    const auto it = sums_.find(id);
    return it != sums_.end() ? &it->second.spread : nullptr;
  }

  // Ends the scan: the gates of whatever runs after it (relocalisation) see no spread.
  void clear() { sums_.clear(); }

 private:
  // Per landmark, the weighted sums over the particles that predict it, then the spread they give.
  struct Sum {
    Vec2 reference;
    double w = 0.0;
    Vec2 first = Vec2::Zero();
    Mat2 second = Mat2::Zero();
    Mat2 spread = Mat2::Zero();
  };
  std::vector<std::vector<PredictedMeasurement>> predicted_;
  std::unordered_map<LandmarkId, Sum> sums_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_SET_SPREAD_H_
