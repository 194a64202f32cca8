// A surveyed prior map; see survey.h.
#include "experiments/sim/survey.h"

#include <limits>

#include "core/engine/rng.h"

namespace arbor {

std::vector<Landmark> surveyed_map(const Scenario& scenario, double sigma_m, std::uint64_t seed, float log_odds) {
  std::vector<Landmark> map;
  map.reserve(scenario.truth_landmarks.size());
  double y0 = std::numeric_limits<double>::infinity();
  for (const TruthLandmark& t : scenario.truth_landmarks) {
    // One stream per landmark, keyed by its true id: the draw does not depend on the file's order.
    RandomStream rng(seed, static_cast<std::uint64_t>(t.id), 0, RandomPurpose::kSurvey);
    Landmark lm;
    lm.mean.x() = t.position.x() + sigma_m * rng.normal();
    lm.mean.y() = t.position.y() + sigma_m * rng.normal();
    lm.cov = Mat2::Identity() * (sigma_m * sigma_m);
    lm.truth_label = t.id;
    lm.log_odds = log_odds;
    lm.confirmed = true;
    y0 = std::min(y0, lm.mean.y());
    map.push_back(lm);
  }
  number_in_strips(map, 30.0, y0);
  return map;
}

}  // namespace arbor
