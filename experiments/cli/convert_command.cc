// `arbor convert`: a raw dataset (Victoria Park, UTIAS MRCLAM, ACFR Car Park, the iSAM Victoria Park file)
// into the scenario format, the one path into the engine. Prints what was dropped and why.
#include <string>

#include <fmt/core.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/metrics/gps_jumps.h"
#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"
#include "experiments/loaders/acfr_car_park.h"
#include "experiments/loaders/isam_victoria_park.h"
#include "experiments/loaders/noise_estimation.h"
#include "experiments/loaders/utias_mrclam.h"
#include "experiments/loaders/victoria_park.h"

namespace arbor::cli {
namespace {

struct ConvertOptions {
  std::string from;
  std::string input;
  int robot = 1;
  std::string out;
  bool estimate_noise = false;
  bool strict = false;
  double max_gps_speed = 0.0;
  double noise_window_s = 1.0;
};

// GPS noise allowance of the jump test: fixes within this of where the vehicle could have driven are kept.
constexpr double kGpsSlackM = 1.0;

std::string default_input(const std::string& from) {
  const std::string data = std::string(ARBOR_SOURCE_DIR) + "/data/";
  if (from == "victoria-park") return data + "victoria_park";
  if (from == "utias-mrclam") return data + "utias_mrclam/MRCLAM_Dataset6";
  if (from == "acfr-car-park") return data + "acfr_car_park";
  return data + "victoria_park/isam_gtsam/victoria_park.txt";
}

// --estimate-noise asks for estimates: data that give none (no residual, no motion window) used to write the
// documented defaults without a word (hostile B9).
void require_estimates(std::int64_t residuals, std::int64_t windows, const std::string& input) {
  if (residuals == 0 || windows == 0)
    throw InputError("", 0, "--estimate-noise",
                     fmt::format("{} gives nothing to estimate the {} noise from ({} measurement residuals, {} motion "
                                 "windows); leave out --estimate-noise to write the documented defaults",
                                 input, residuals == 0 ? "measurement" : "motion", residuals, windows));
}

void print_measurement_estimate(const MeasurementNoiseEstimate& m) {
  fmt::print("  measurement noise from {} residuals: sigma_range {:.4f} m (MAD {:.4f}, bias {:+.4f}), sigma_bearing "
             "{:.4f} rad (MAD {:.4f}, bias {:+.4f}); beyond 3 sigma {:.1f} %, beyond 5 sigma (dropped) {:.1f} %\n",
             m.count, m.sigma_range_m, m.mad_sigma_range_m, m.range_bias_m, m.sigma_bearing_rad, m.mad_sigma_bearing_rad,
             m.bearing_bias_rad, 100.0 * m.beyond_3sigma_fraction, 100.0 * m.outlier_fraction);
}

int run_convert(const ConvertOptions& o) {
  const std::string input = o.input.empty() ? default_input(o.from) : o.input;
  LoadReport report;
  Scenario scenario;
  if (o.from == "victoria-park") {
    if (o.estimate_noise)
      throw InputError("", 0, "--estimate-noise", "Victoria Park has no ground truth for the trees or the heading; its noise values are documented tuning defaults");
    scenario = load_victoria_park(input, &report);
  } else if (o.from == "utias-mrclam") {
    UtiasOptions options;
    options.robot = o.robot;
    options.strict_barcodes = o.strict;
    scenario = load_utias_mrclam(input, options, &report);
    if (o.estimate_noise) {
      const MeasurementNoiseEstimate m = estimate_measurement_noise(scenario);
      const MotionNoiseEstimate u = estimate_motion_noise(scenario, o.noise_window_s);
      print_measurement_estimate(m);
      fmt::print("  motion noise from {} windows of {} s: q_v {:.3g} m^2/s (MAD {:.3g}), q_omega {:.3g} rad^2/s (MAD {:.3g})\n",
                 u.windows, o.noise_window_s, u.q_1, u.mad_q_1, u.q_2, u.mad_q_2);
      require_estimates(m.count, u.windows, input);
      apply_noise_estimates(m, u, &scenario);
    }
  } else if (o.from == "acfr-car-park") {
    scenario = load_acfr_car_park(input, &report);
    if (o.estimate_noise) {
      const CarParkNoiseEstimate e = estimate_car_park_noise(scenario);
      fmt::print("  {} scans with >= 3 beacons fitted; GPS-to-laser lever arm ({:.2f}, {:.2f}) m\n", e.fitted_scans,
                 e.gps_to_laser_m.x(), e.gps_to_laser_m.y());
      print_measurement_estimate(e.measurement);
      fmt::print("  motion noise from {} windows of 2 s on the GPS track: q_v {:.3g} m^2/s (MAD {:.3g}), q_steer {:.3g} "
                 "rad^2 s (MAD {:.3g})\n", e.motion.windows, e.motion.q_1, e.motion.mad_q_1, e.motion.q_2, e.motion.mad_q_2);
      require_estimates(e.measurement.count, e.motion.windows, input);
      apply_noise_estimate(e, &scenario);
    }
  } else if (o.from == "isam") {
    if (o.estimate_noise) throw InputError("", 0, "--estimate-noise", "the iSAM file states its own covariances; nothing to estimate");
    const IsamDataset d = read_isam_dataset(input);
    scenario = isam_to_scenario(d, input);
    report.add("poses", static_cast<std::int64_t>(d.pose_ids.size()));
    report.add("landmarks", static_cast<std::int64_t>(d.landmark_ids.size()));
    report.add("observations", static_cast<std::int64_t>(d.observations.size()));
    report.add("steps", static_cast<std::int64_t>(scenario.steps.size()));
  }
  if (o.max_gps_speed > 0.0) {
    if (scenario.truth_track.empty()) throw InputError("", 0, "--max-gps-speed", "this dataset has no GPS track");
    int dropped = 0;
    scenario.truth_track = drop_gps_jumps(scenario.truth_track, o.max_gps_speed, kGpsSlackM, &dropped);
    report.add("dropped: GPS jump", dropped);
  }
  write_scenario(scenario, o.out);
  fmt::print("converted {} ({}) -> {}\n", o.from, input, o.out);
  for (const auto& [what, n] : report.counts) fmt::print("  {}: {}\n", what, n);
  for (const auto& [what, text] : report.notes) fmt::print("  {}: {}\n", what, text);
  return 0;
}

}  // namespace

void add_convert_command(CLI::App& app, CommandAction* action) {
  auto options = std::make_shared<ConvertOptions>();
  CLI::App* cmd = app.add_subcommand("convert", "Convert a raw real dataset into an Arbor scenario file");
  cmd->add_option("--from", options->from, "Dataset format")
      ->required()
      ->check(CLI::IsMember({"victoria-park", "utias-mrclam", "acfr-car-park", "isam"}));
  cmd->add_option("--input", options->input,
                  "Dataset directory (victoria-park, utias-mrclam, acfr-car-park) or file (isam); default: the copy "
                  "shipped in data/");
  cmd->add_option("--robot", options->robot, "UTIAS MRCLAM: which robot (subject number, 1-5)")->check(at_least(1));
  cmd->add_option("--out", options->out, "Scenario file to write")->required();
  cmd->add_flag("--estimate-noise", options->estimate_noise,
                "UTIAS, Car Park: estimate measurement and motion noise from ground truth (the standard "
                "deviation within 5 sigma; 1.4826 x MAD reported beside it) and write the estimates into the scenario "
                "instead of the documented defaults");
  cmd->add_flag("--strict", options->strict,
                "UTIAS: treat unknown barcodes (known false detections) as errors instead of dropping and counting them");
  cmd->add_option("--noise-window", options->noise_window_s,
                  "UTIAS --estimate-noise: length [s] of the replayed motion windows (the command errors are correlated "
                  "in time, so the density grows with the window; choose about the time between scans)")
      ->check(within(0.05, 60.0))
      ->capture_default_str();
  cmd->add_option("--max-gps-speed", options->max_gps_speed,
                  "Victoria Park, Car Park: drop GPS fixes that imply more than this speed [m/s] from the last kept fix "
                  "(GPS jumps; 0 keeps every fix). The ute's top speed in the data is 6.6 m/s")
      ->check(at_least(0))
      ->capture_default_str();
  cmd->callback([options, action] { *action = [options] { return run_convert(*options); }; });
}

}  // namespace arbor::cli
