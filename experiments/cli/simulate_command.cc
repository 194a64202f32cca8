// `arbor simulate`: writes a simulated scenario (world, loop trajectory, noisy odometry and measurements,
// ground truth) in the scenario text format.
#include <fmt/core.h>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "experiments/cli/commands.h"
#include "experiments/options/simulation_options.h"

namespace arbor::cli {

void add_simulate_command(CLI::App& app, CommandAction* action) {
  auto* cmd = app.add_subcommand("simulate", "Write a simulated scenario with ground truth (deterministic from --seed)");
  auto choices = std::make_shared<SimulationChoices>();
  auto out = std::make_shared<std::string>();
  add_simulation_options(*cmd, *choices);
  cmd->add_option("--out", *out, "Scenario file to write")->required();
  *action = nullptr;
  cmd->callback([=] {
    *action = [=] {
      const Scenario scenario = simulate(simulation_options(*choices));
      write_scenario(scenario, *out);
      std::size_t measurements = 0;
      for (const auto& s : scenario.steps) measurements += s.measurements.size();
      fmt::print("wrote {}: {} world, {} landmarks, {} steps, {} measurements\n", *out, choices->world,
                 scenario.truth_landmarks.size(), scenario.steps.size(), measurements);
      return 0;
    };
  });
}

}  // namespace arbor::cli
