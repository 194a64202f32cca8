// Ceres smoother solve time on the pre-associated Victoria Park file (iSAM/GTSAM format; DESIGN.md §10
// target: < 1 s on 2 cores) and, when given, on scenario files with true association: both sparse linear
// solvers, 1 and 2 threads, with and without the warm start. The solve is timed from the initial values each iteration (setup outside).
// Inputs: ARBOR_ISAM_FILE (default data/victoria_park/isam_gtsam/victoria_park.txt under the source tree),
// ARBOR_SMOOTH_SCENARIOS (colon-separated scenario files; optional).
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/core.h>

#include "core/io/scenario_format.h"
#include "experiments/loaders/isam_factor_graph.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

void BM_Smoother_Solve(benchmark::State& state, std::shared_ptr<const FactorGraph> graph, SmootherOptions options) {
  options.threads = static_cast<int>(state.range(0));
  SmootherSummary last;
  for (auto _ : state) {
    SmootherResult r = solve_factor_graph(*graph, options);
    benchmark::DoNotOptimize(r.poses.data());
    last = r.summary;
  }
  state.counters["solve_s"] = last.solve_time_s;
  state.counters["solve_cpu_s"] = last.solve_cpu_s;
  state.counters["iterations"] = last.iterations;
  state.counters["initial_cost"] = last.initial_cost;
  state.counters["final_cost"] = last.final_cost;
  state.counters["converged"] = last.termination == "CONVERGENCE";
  state.counters["poses"] = last.poses;
  state.counters["landmarks"] = last.landmarks;
  state.counters["factors"] = last.factors;
}

// The default options, each linear solver, the landmarks-first Schur ordering, and no warm start.
void register_graph(const std::string& name, std::shared_ptr<const FactorGraph> graph) {
  struct Variant {
    std::string label;
    SmootherOptions options;
  };
  std::vector<Variant> variants;
  for (SmootherLinearSolver solver : {SmootherLinearSolver::kSparseNormalCholesky, SmootherLinearSolver::kSparseSchur}) {
    SmootherOptions o;
    o.linear_solver = solver;
    variants.push_back({fmt::format("solver:{}/start:warm", to_string(solver)), o});
    o.warm_start_poses = 0;
    variants.push_back({fmt::format("solver:{}/start:batch", to_string(solver)), o});
  }
  SmootherOptions landmarks_first;
  landmarks_first.linear_solver = SmootherLinearSolver::kSparseSchur;
  landmarks_first.schur_landmarks_first = true;
  variants.push_back({"solver:sparse-schur-landmarks-first/start:warm", landmarks_first});
  for (const Variant& v : variants) {
    benchmark::RegisterBenchmark(fmt::format("BM_Smoother_Solve/data:{}/{}", name, v.label).c_str(), BM_Smoother_Solve,
                                 graph, v.options)
        ->ArgName("threads")
        ->Arg(1)
        ->Arg(2)
        ->Unit(benchmark::kMillisecond)
        ->UseRealTime();
  }
}

std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v ? std::string(v) : fallback;
}

}  // namespace
}  // namespace arbor

int main(int argc, char** argv) {
  using namespace arbor;
  benchmark::Initialize(&argc, argv);
  const std::string isam =
      env_or("ARBOR_ISAM_FILE", std::string(ARBOR_SOURCE_DIR) + "/data/victoria_park/isam_gtsam/victoria_park.txt");
  if (std::filesystem::exists(isam)) {
    register_graph("victoria_park_isam", std::make_shared<const FactorGraph>(read_isam_factor_graph(isam)));
  } else {
    fmt::print(stderr, "smoother_benchmark: {} not found (set ARBOR_ISAM_FILE); skipping Victoria Park\n", isam);
  }
  std::stringstream scenarios(env_or("ARBOR_SMOOTH_SCENARIOS", ""));
  for (std::string path; std::getline(scenarios, path, ':');) {
    if (path.empty()) continue;
    const Scenario s = read_scenario(path);
    const SmootherAssociations truth = SmootherAssociations::from_truth(s);
    register_graph(std::filesystem::path(path).stem().string(),
                   std::make_shared<const FactorGraph>(build_factor_graph(s, truth, SmootherOptions{})));
  }
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
