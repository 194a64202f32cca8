// `arbor simulate`: writes a simulated scenario (world, loop trajectory, noisy odometry and measurements,
// ground truth) in the scenario text format.
#include <filesystem>

#include <fmt/core.h>

#include "core/engine/fastslam_options.h"
#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/trajectory_io.h"
#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"
#include "experiments/options/simulation_options.h"
#include "experiments/sim/survey.h"

namespace arbor::cli {

void add_simulate_command(CLI::App& app, CommandAction* action) {
  auto* cmd = app.add_subcommand("simulate", "Write a simulated scenario with ground truth (deterministic from --seed)");
  auto choices = std::make_shared<SimulationChoices>();
  auto out = std::make_shared<std::string>();
  auto survey_out = std::make_shared<std::string>();
  auto survey_sigma = std::make_shared<double>(0.05);
  add_simulation_options(*cmd, *choices);
  cmd->add_option("--out", *out, "Scenario file to write")->required();
  cmd->add_option("--survey-out", *survey_out,
                  "Also write a surveyed map of every true landmark (map.csv), for `arbor run --prior-map`");
  cmd->add_option("--survey-sigma", *survey_sigma, "Survey error standard deviation [m], per axis")
      ->check(within(1e-6, 1e3))
      ->capture_default_str();
  *action = nullptr;
  cmd->callback([=] {
    *action = [=] {
      if (!survey_out->empty() && std::filesystem::weakly_canonical(*survey_out) == std::filesystem::weakly_canonical(*out))
        throw InputError("", 0, "survey-out", fmt::format("--survey-out {} is the scenario file --out; give it its own", *survey_out));
      const Scenario scenario = simulate(simulation_options(*choices));
      write_scenario(scenario, *out);
      std::size_t measurements = 0;
      for (const auto& s : scenario.steps) measurements += s.measurements.size();
      fmt::print("wrote {}: {} world, {} landmarks, {} steps, {} measurements\n", *out, choices->world,
                 scenario.truth_landmarks.size(), scenario.steps.size(), measurements);
      if (!survey_out->empty()) {
        // As established as the filter's existence cap allows: a survey is not a single sighting.
        const float log_odds = static_cast<float>(FastSlamOptions{}.log_odds_max);
        write_map_csv(*survey_out, surveyed_map(scenario, *survey_sigma, choices->options.seed, log_odds));
        fmt::print("wrote {}: {} surveyed landmarks, sigma {} m\n", *survey_out, scenario.truth_landmarks.size(),
                   *survey_sigma);
      }
      return 0;
    };
  });
}

}  // namespace arbor::cli
