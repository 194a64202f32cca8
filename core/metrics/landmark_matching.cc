// One-to-one landmark pairing by distance for maps without ground-truth ids.
#include "core/metrics/landmark_matching.h"

#include <algorithm>
#include <cmath>
#include <tuple>

namespace arbor {

std::optional<MatchedLandmarkError> matched_landmark_rmse(const std::vector<Landmark>& map,
                                                          const std::vector<TruthLandmark>& truth, double gate_m,
                                                          const Pose2& alignment) {
  if (map.empty() || truth.empty()) return std::nullopt;
  std::vector<std::tuple<double, std::size_t, std::size_t>> pairs;  // (distance, map index, truth index)
  for (std::size_t i = 0; i < map.size(); ++i) {
    const Vec2 p = alignment.transform(map[i].mean);
    for (std::size_t j = 0; j < truth.size(); ++j) {
      const double d = (p - truth[j].position).norm();
      if (d < gate_m) pairs.emplace_back(d, i, j);
    }
  }
  std::sort(pairs.begin(), pairs.end());
  std::vector<bool> map_used(map.size(), false), truth_used(truth.size(), false);
  MatchedLandmarkError out;
  double sum = 0.0;
  for (const auto& [d, i, j] : pairs) {
    if (map_used[i] || truth_used[j]) continue;
    map_used[i] = truth_used[j] = true;
    sum += d * d;
    ++out.matched;
  }
  if (out.matched == 0) return std::nullopt;
  out.rmse_m = std::sqrt(sum / out.matched);
  out.unmatched = static_cast<int>(map.size()) - out.matched;
  out.missed = static_cast<int>(truth.size()) - out.matched;
  return out;
}

}  // namespace arbor
