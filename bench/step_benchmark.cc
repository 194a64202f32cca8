// One FastSLAM step (predict, associate, update, weight, resample) vs N = 10^2..10^6 landmarks (to
// ARBOR_BENCH_MAX_N) at constant
// density, M = 100 particles, for every map back end: the complexity figure of DESIGN.md §3.
// The particles start from a shared prior map of N landmarks (set_prior_map) and drive a circle through it,
// so the landmarks in view per scan stay the same whatever N. Step time is the process's CPU time (manual
// time), one thread and M = 100 unless ARBOR_BENCH_THREADS / ARBOR_BENCH_PARTICLES say otherwise. Run through bench/run_map_benchmarks.sh.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include <time.h>

#include <benchmark/benchmark.h>

#include "bench/live_bytes.h"
#include "bench/map_world.h"
#include "core/engine/ekf_slam.h"
#include "core/engine/fastslam.h"
#include "variants/registry.h"

namespace arbor::bench {
namespace {

constexpr int kWarmupSteps = 20;
constexpr int kTimedSteps = 100;
// The naive back end keeps M full copies (and 2M while resampling): 10^6 x 96 B x 200 would need 19 GB.
constexpr std::int64_t kNaiveMaxN = 100000;

// CPU seconds of the whole process (all threads): on a shared machine, wall time also counts the time other
// jobs held the core, which at ~0.5 ms per step would dominate the tail.
double process_cpu_s() {
  timespec ts;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// The timed steps' median and p95 CPU time and their measurements per step, as the plot script reads them.
void record_step_times(benchmark::State& state, std::vector<double> seconds, std::int64_t measurements) {
  std::sort(seconds.begin(), seconds.end());
  state.counters["step_median_s"] = seconds[seconds.size() / 2];
  state.counters["step_p95_s"] = seconds[std::min(seconds.size() - 1, seconds.size() * 95 / 100)];
  state.counters["measurements_per_step"] = static_cast<double>(measurements) / seconds.size();
}

// A drive of `steps` scans on a circle through the field of n landmarks, as far from its edge at every N.
Scenario circle_through(const std::vector<Landmark>& field, std::int64_t n, int steps) {
  FieldDrive drive;
  drive.radius_m = std::min(0.3 * field_side_m(n), 100.0);
  drive.steps = steps;
  return make_field_scenario(field, drive);
}

template <class Map>
void BM_FastSlam_Step(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const int threads = static_cast<int>(state.range(1));
  const int particles = static_cast<int>(state.range(2));
  const auto field = make_landmark_field(n);
  const Scenario scenario = circle_through(field, n, kWarmupSteps + kTimedSteps);

  FastSlamOptions options;
  options.particles = particles;
  options.threads = threads;
  options.seed = 1;
  FastSlam<Map, KnownAssociation> engine(scenario, options);
  {
    Map prior;
    for (const Landmark& lm : field) prior.insert(lm);
    engine.set_prior_map(prior);
  }
  int k = 0;
  for (; k < kWarmupSteps; ++k) engine.step(scenario.steps[k]);

  std::vector<double> seconds, wall;
  std::int64_t measurements = 0, resamples = 0;
  for (auto _ : state) {
    const auto start = std::chrono::steady_clock::now();
    const double cpu_start = process_cpu_s();
    engine.step(scenario.steps[k]);
    seconds.push_back(process_cpu_s() - cpu_start);
    wall.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    state.SetIterationTime(seconds.back());
    measurements += static_cast<std::int64_t>(scenario.steps[k].measurements.size());
    resamples += engine.last_step_stats().resampled;
    ++k;
  }
  record_step_times(state, seconds, measurements);
  std::sort(wall.begin(), wall.end());
  state.counters["step_wall_median_s"] = wall[wall.size() / 2];
  state.counters["resample_fraction"] = static_cast<double>(resamples) / seconds.size();
  state.counters["landmarks_best"] = static_cast<double>(engine.last_step_stats().best_landmarks);
  const MapMemoryStats total = engine.memory_stats();
  state.counters["owned_bytes_per_particle"] = static_cast<double>(total.bytes - total.shared_bytes) / particles;
  // Distinct bytes held by all particles together, per particle: the pool's count where the back end has one
  // (the prior map was dropped above, so the particles hold all of it), else the sum (nothing is shared).
  const std::int64_t pool = live_bytes<Map>();
  state.counters["bytes_per_particle"] =
      (pool >= 0 ? static_cast<double>(pool) : static_cast<double>(total.bytes)) / particles;
}

// EKF-SLAM's step on the same worlds, from the same prior map: the O(N^2) update Probabilistic Robotics
// §13.8 sets against FastSLAM's O(M log N). Its state is (3 + 2N)^2 doubles, 3.2 GB at N = 10^4, and a step
// there takes seconds, so it stops at ARBOR_BENCH_EKF_MAX_N (10^4) and times fewer steps.
constexpr int kEkfWarmupSteps = 3;
constexpr int kEkfTimedSteps = 12;

void BM_Ekf_Step(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const auto field = make_landmark_field(n);
  const Scenario scenario = circle_through(field, n, kEkfWarmupSteps + kEkfTimedSteps);
  FastSlamOptions options;
  options.version = FilterVersion::kEkf;
  EkfSlam<VectorMap, KnownAssociation> engine(scenario, options);
  engine.set_prior_map(field);
  int k = 0;
  for (; k < kEkfWarmupSteps; ++k) engine.step(scenario.steps[k]);
  std::vector<double> seconds;
  std::int64_t measurements = 0;
  for (auto _ : state) {
    const double cpu_start = process_cpu_s();
    engine.step(scenario.steps[k]);
    seconds.push_back(process_cpu_s() - cpu_start);
    state.SetIterationTime(seconds.back());
    measurements += static_cast<std::int64_t>(scenario.steps[k].measurements.size());
    ++k;
  }
  record_step_times(state, seconds, measurements);
  state.counters["landmarks_best"] = static_cast<double>(engine.last_step_stats().best_landmarks);
  state.counters["bytes_per_particle"] = static_cast<double>(engine.state().bytes());  // the one estimate's
}

void register_ekf() {
  const char* max = std::getenv("ARBOR_BENCH_EKF_MAX_N");
  const std::int64_t max_n = max ? std::atoll(max) : 10000;
  auto* b = benchmark::RegisterBenchmark("BM_FastSlam_Step/backend:ekf", BM_Ekf_Step);
  b->ArgNames({"n"})->UseManualTime()->Iterations(kEkfTimedSteps)->Unit(benchmark::kMicrosecond);
  for (std::int64_t n : {100, 300, 1000, 3000, 10000, 30000})
    if (n <= max_n) b->Args({n});
}

template <class... Maps>
void register_all(TypeList<Maps...>) {
  auto env = [](const char* name, int fallback) { return std::getenv(name) ? std::atoi(std::getenv(name)) : fallback; };
  const int threads = env("ARBOR_BENCH_THREADS", 1);
  const int particles = env("ARBOR_BENCH_PARTICLES", 100);
  (
      [&] {
        const std::string name = std::string("BM_FastSlam_Step/backend:") + std::string(Maps::kName);
        auto* b = benchmark::RegisterBenchmark(name.c_str(), BM_FastSlam_Step<Maps>);
        b->ArgNames({"n", "threads", "particles"})->UseManualTime()->Iterations(kTimedSteps)->Unit(benchmark::kMicrosecond);
        const bool naive = Maps::kName == std::string_view("naive");
        for (std::int64_t n = 100; n <= bench_max_n(); n *= 10)
          if (!naive || n <= kNaiveMaxN) b->Args({n, threads, particles});
      }(),
      ...);
}

}  // namespace
}  // namespace arbor::bench

int main(int argc, char** argv) {
  arbor::bench::register_all(arbor::MapBackends{});
  arbor::bench::register_ekf();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
