// The simulation options, defined once; see simulation_options.h.
#include "experiments/options/simulation_options.h"

#include <algorithm>

#include <CLI/CLI.hpp>

#include "core/io/input_error.h"
#include "experiments/options/option_checks.h"

namespace arbor::cli {

void add_simulation_options(CLI::App& cmd, SimulationChoices& choices) {
  SimulationOptions& options = choices.options;
  cmd.add_option("--world", choices.world, "World layout: uniform, clustered, or rooms (walls block sight)")
      ->check(CLI::IsMember({"uniform", "clustered", "rooms"}))
      ->capture_default_str();
  cmd.add_option("--landmarks", options.world.landmarks, "Number of landmarks N; the world's area grows with N")
      ->capture_default_str();
  cmd.add_option("--density", options.world.density_per_m2,
                 "Landmarks per square metre (keeps the number in view per scan constant as N grows)")
      ->capture_default_str();
  cmd.add_option("--steps", options.steps, "Number of scans (with --controls-per-scan K, K odometry readings each)")
      ->capture_default_str();
  cmd.add_option("--controls-per-scan", options.controls_per_scan,
                 "Odometry readings between two scans, as real robots log them (the noise is continuous-time, so "
                 "the truth's statistics do not depend on K)")
      ->capture_default_str();
  cmd.add_option("--clutter", options.clutter_rate, "Expected spurious measurements per scan (Poisson rate)")
      ->capture_default_str();
  cmd.add_option("--detection", options.detection_probability, "Probability that a landmark in view is detected")
      ->capture_default_str();
  cmd.add_option("--range", options.sensor.max_range_m, "Sensor range [m]")->capture_default_str();
  cmd.add_option("--fov", options.sensor.fov_rad, "Sensor field of view [rad], centred on the heading")
      ->capture_default_str();
  cmd.add_option("--sigma-range", options.sensor.sigma_range_m, "Range noise standard deviation [m]")
      ->capture_default_str();
  cmd.add_option("--sigma-bearing", options.sensor.sigma_bearing_rad, "Bearing noise standard deviation [rad]")
      ->capture_default_str();
  cmd.add_option("--odometry-noise", choices.odometry_noise,
                 "Odometry noise densities q_v q_omega k_v k_wv k_ww: speed [m^2/s], turn rate [rad^2/s], "
                 "distance variance per metre [m], heading variance per metre [rad^2/m] and per radian turned "
                 "[rad^2/rad] (docs/scenario_format.md)")
      ->expected(5);
  cmd.add_option("--kidnap", options.kidnap_time_s,
                 "Kidnapped robot: at the first scan at or after this time [s], carry the robot unseen by its odometer "
                 "to where it was at half that time, and drive on from there")
      ->check(at_least(0));
  cmd.add_flag("--signatures", options.signatures, "Report a noisy scalar signature with each measurement");
  cmd.add_option("--seed", options.seed, "Seed of the world and of all noise")
      ->check(unsigned_number())
      ->capture_default_str();
}

SimulationOptions simulation_options(const SimulationChoices& choices) {
  SimulationOptions options = choices.options;
  if (!from_string(choices.world, &options.world.kind)) throw InputError("", 0, "world", "unknown world " + choices.world);
  options.world.seed = options.seed;
  if (!choices.odometry_noise.empty()) {
    for (double a : choices.odometry_noise)
      if (!(a >= 0.0)) throw InputError("", 0, "odometry-noise", "noise parameters must not be negative");
    const auto& q = choices.odometry_noise;
    options.odometry = OdometryNoise{q[0], q[1], q[2], q[3], q[4]};
  }
  return options;
}

SimulationOptions simulation_options_from_arguments(std::vector<std::string> arguments) {
  CLI::App app;
  SimulationChoices choices;
  add_simulation_options(app, choices);
  apply_common_option_checks(app);
  std::reverse(arguments.begin(), arguments.end());  // CLI11 takes a vector of arguments last first
  try {
    app.parse(arguments);
  } catch (const CLI::ParseError& e) {
    throw InputError("", 0, "", e.what());
  }
  return simulation_options(choices);
}

}  // namespace arbor::cli
