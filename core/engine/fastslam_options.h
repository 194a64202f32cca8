// Options of the FastSLAM engine, with defaults a user can run as they are.
#ifndef ARBOR_CORE_ENGINE_FASTSLAM_OPTIONS_H_
#define ARBOR_CORE_ENGINE_FASTSLAM_OPTIONS_H_

#include <cstdint>
#include <string>
#include <string_view>

#include "core/association/association_problem.h"

namespace arbor {

enum class FilterVersion { kFastSlam1, kFastSlam2 };

std::string_view to_string(FilterVersion version);
bool from_string(std::string_view name, FilterVersion* version);

struct FastSlamOptions {
  FilterVersion version = FilterVersion::kFastSlam2;
  int particles = 100;
  std::uint64_t seed = 1;
  int threads = 0;                  // 0: all hardware threads
  double resample_threshold = 0.5;  // resample when N_eff < threshold * particles
  AssociationOptions association;

  // Landmark existence evidence in log-odds (Montemerlo 2003 §4 uses the same counting idea): seen +hit,
  // predicted in view and missed -miss, clamped at max; below prune the landmark is dropped. Provisional
  // landmarks from clutter are seen once and then missed, so they fall below the threshold within a few scans.
  double log_odds_initial = 1.0;
  double log_odds_hit = 1.0;
  double log_odds_miss = 0.5;
  double log_odds_max = 8.0;
  double log_odds_prune = 0.0;
  // Pruning is off with known association: the ids are right by construction, so evidence only matters
  // when the filter decides what exists.
  bool prune_with_known_association = false;

  // Landmarks near the edge of the sensor's view are association candidates (they may be seen), but only
  // landmarks well inside it are penalised when missed.
  double candidate_range_margin_m = 3.0;
  double candidate_bearing_margin_rad = 0.15;
  double evidence_range_margin_m = 1.0;
  double evidence_bearing_margin_rad = 0.05;

  // Returns an empty string when valid, else what is wrong (Ceres's Options::IsValid idea).
  std::string validate() const;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_FASTSLAM_OPTIONS_H_
