// Victoria Park (ACFR; Guivant & Nebot 2001) into a scenario: 40 Hz dead reckoning with the Ackermann model,
// the tree detections of every laser scan, and the GPS track for evaluation. Facts: data/victoria_park/SOURCE.md.
#ifndef ARBOR_EXPERIMENTS_LOADERS_VICTORIA_PARK_H_
#define ARBOR_EXPERIMENTS_LOADERS_VICTORIA_PARK_H_

#include <cstdint>
#include <string>

#include "core/types/scenario.h"
#include "experiments/loaders/load_report.h"

namespace arbor {

struct VictoriaParkFiles {
  static constexpr const char* kDeadReckoning = "csv_from_mat/aa3_dr.csv";
  static constexpr const char* kGps = "csv_from_mat/aa3_gpsx.csv";
  static constexpr const char* kTrees = "leung_extracted/measurements.dat";
};

// The clock of every raw file is milliseconds; measurements.dat and the scenario use seconds relative to the
// first GPS time stamp, t_s = (t_ms - 20967) / 1000.
inline constexpr std::int64_t kVictoriaParkOriginMs = 20967;

// Tuning choices, not dataset facts (docs/datasets.md says why each was picked).
struct VictoriaParkTuning {
  // Continuous-time densities (AckermannNoise); the per-reading sigmas they equal at the 40 Hz dead reckoning
  // are sqrt(q / 0.025 s).
  double q_v_m2ps = 0.7 * 0.7 * 0.025;       // 0.7 m/s per reading: the ACFR reference filter's speed noise
  double q_steer_rad2s = 0.03 * 0.03 * 0.025;  // 0.03 rad per reading (grid against GPS: docs/datasets.md)
  double sigma_range_m = 0.5;                // tree centre from a trunk of 0.1-1.5 m diameter
  double sigma_bearing_rad = 0.02;           // about 1.1 degrees (0.5 degree beams, trunk width)
  double max_range_m = 30.0;                 // detections beyond it are dropped: rarely re-detected, poorly placed
};

// dir holds the layout of data/victoria_park (the three files above). Every line is checked: column count,
// numbers, time order, ranges and bearings in the laser's span; an error names file, line and field.
Scenario load_victoria_park(const std::string& dir, LoadReport* report, const VictoriaParkTuning& tuning = {});

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_VICTORIA_PARK_H_
