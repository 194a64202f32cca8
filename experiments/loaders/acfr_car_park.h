// ACFR Car Park (Nieto & Nebot, ACFR SLAM summer school) into a scenario: the Victoria Park ute's dead
// reckoning, reflector beacons extracted from the raw laser ranges and intensities, the surveyed beacons as
// landmark ground truth and GPS as the evaluation track. Facts: data/acfr_car_park/SOURCE.md.
#ifndef ARBOR_EXPERIMENTS_LOADERS_ACFR_CAR_PARK_H_
#define ARBOR_EXPERIMENTS_LOADERS_ACFR_CAR_PARK_H_

#include <string>
#include <vector>

#include "core/types/scenario.h"
#include "experiments/loaders/load_report.h"
#include "experiments/loaders/noise_estimation.h"

namespace arbor {

// Beacon extraction: a run of consecutive beams with a reflective return (intensity > 0) within the range
// window, whose neighbouring ranges differ by less than max_range_jump_m, is one pole. Its range is the mean
// range plus the pole's radius (the laser hits the near surface of a 6 cm pole), its bearing the mean beam angle.
struct BeaconExtraction {
  double min_range_m = 1.0;  // closer returns are the vehicle itself (ACFR reference: 1 m < r < 30 m)
  double max_range_m = 30.0;
  double max_range_jump_m = 0.5;
  double pole_radius_m = 0.03;
};

// One laser scan (361 beams, 0.5 degree apart, beam 0 = vehicle's right) to vehicle-frame measurements.
std::vector<Measurement> extract_beacons(const std::vector<double>& ranges_m, const std::vector<double>& intensity,
                                         const BeaconExtraction& options = {});

// Noise defaults measured by estimate_car_park_noise on the shipped data (docs/datasets.md): standard
// deviations within 5 sigma and continuous-time motion densities over 2 s windows of the GPS track.
struct CarParkNoiseDefaults {
  static constexpr double kSigmaRangeM = 0.0196;
  static constexpr double kSigmaBearingRad = 0.0058;
  static constexpr double kQvM2ps = 1.22e-3;      // wheel-speed density [m^2/s]
  static constexpr double kQsteerRad2s = 9.1e-4;  // steering density [rad^2 s]
};

Scenario load_acfr_car_park(const std::string& dir, LoadReport* report, const BeaconExtraction& extraction = {});

// Ground truth for noise estimation: the laser pose at scans that see >= 3 beacons, fitted in closed form
// (2-D rigid alignment) to the surveyed positions after associating each detection with the nearest surveyed
// beacon from a GPS-based guess (GPS position plus a lever arm estimated in a first pass, heading from the
// GPS track). Measurement residuals are scaled by sqrt(n / (n - 3 per fitted scan)) for the fitted dof.
struct CarParkNoiseEstimate {
  MeasurementNoiseEstimate measurement;
  MotionNoiseEstimate motion;
  std::int64_t fitted_scans = 0;
  Vec2 gps_to_laser_m = Vec2::Zero();  // lever arm in the vehicle frame (x ahead, y left)
};
CarParkNoiseEstimate estimate_car_park_noise(const Scenario& scenario);
// What `convert --estimate-noise` does with it: the measurement noise and the Ackermann densities replace the
// documented defaults where they rest on data.
void apply_noise_estimate(const CarParkNoiseEstimate& estimate, Scenario* scenario);

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_ACFR_CAR_PARK_H_
