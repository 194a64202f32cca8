// The options of `arbor simulate`, defined once: the command line and the Python API's arbor.simulate parse
// the same names, defaults and checks.
#ifndef ARBOR_EXPERIMENTS_OPTIONS_SIMULATION_OPTIONS_H_
#define ARBOR_EXPERIMENTS_OPTIONS_SIMULATION_OPTIONS_H_

#include <string>
#include <vector>

#include "experiments/sim/simulator.h"

namespace CLI {
class App;
}  // namespace CLI

namespace arbor::cli {

// What the command line binds; simulation_options() turns it into the simulator's options.
struct SimulationChoices {
  SimulationOptions options;
  std::string world = "uniform";
  std::vector<double> odometry_noise;  // empty: the simulator's default
};

// Adds every simulation option except --out to cmd, bound to choices.
void add_simulation_options(CLI::App& cmd, SimulationChoices& choices);

// Checks what parsing cannot and returns the simulator's options; throws InputError naming the option.
SimulationOptions simulation_options(const SimulationChoices& choices);

// Parses `--name=value` arguments as `arbor simulate` parses its command line; throws InputError with
// CLI11's message.
SimulationOptions simulation_options_from_arguments(std::vector<std::string> arguments);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_OPTIONS_SIMULATION_OPTIONS_H_
