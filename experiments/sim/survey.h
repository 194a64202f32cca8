// A surveyed prior map of a simulated world (`arbor simulate --survey-out`), the map `arbor run --prior-map`
// starts from: localisation in a known map, or a run at a map size no robot could build in a test's time.
#ifndef ARBOR_EXPERIMENTS_SIM_SURVEY_H_
#define ARBOR_EXPERIMENTS_SIM_SURVEY_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/types/landmark.h"
#include "core/types/scenario.h"

namespace arbor {

// Numbers the landmarks 0..n-1 in the order of a boustrophedon sweep in strips of strip_width_m along x,
// counted from y = y0_m, and sorts them so. This is the order in which a robot sweeping the area would
// create them, so ids close in value are landmarks close in space: the trie (identity hash) and the tree
// keep tight bounding boxes. Random ids would make every box span the whole world.
inline void number_in_strips(std::vector<Landmark>& landmarks, double strip_width_m, double y0_m) {
  auto strip = [&](const Landmark& lm) { return static_cast<std::int64_t>((lm.mean.y() - y0_m) / strip_width_m); };
  std::sort(landmarks.begin(), landmarks.end(), [&](const Landmark& a, const Landmark& b) {
    const std::int64_t sa = strip(a), sb = strip(b);
    if (sa != sb) return sa < sb;
    return (sa % 2 == 0) ? a.mean.x() < b.mean.x() : a.mean.x() > b.mean.x();
  });
  for (std::size_t i = 0; i < landmarks.size(); ++i) landmarks[i].id = static_cast<LandmarkId>(i);
}

// Every true landmark of the scenario, measured by a survey with isotropic error sigma_m: the mean is the
// truth plus a seeded N(0, sigma_m^2 I) draw, the covariance sigma_m^2 I (so the map is consistent), ids in
// strip order (number_in_strips, 30 m strips), truth_label the true id, confirmed, log-odds log_odds.
std::vector<Landmark> surveyed_map(const Scenario& scenario, double sigma_m, std::uint64_t seed, float log_odds);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_SIM_SURVEY_H_
