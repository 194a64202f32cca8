// Map back end micro-benchmarks at N = 10^2..10^6 landmarks (ARBOR_BENCH_MAX_N=10000000: to 10^7): one set on a map shared with its parent, a
// particle copy, a spatial query, the memory of M = 100 particles that each updated a few landmarks, and (at
// 10^5) the memory a filter's lineage of such particles holds after 1000 steps.
// Run: build/bench/map_benchmark --benchmark_out=FILE.json (see analysis/studies/plot_map_complexity.py).
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench/live_bytes.h"
#include "bench/map_world.h"
#include "core/types/box2.h"
#include "variants/registry.h"

namespace arbor::bench {
namespace {

constexpr int kParticles = 100;
constexpr int kSetsPerParticle = 5;
constexpr int kPrecomputed = 4096;

// The parent map of the last (backend, N) asked for, kept between benchmarks (building 10^6 costs seconds).
template <class M>
const M& parent_map(std::int64_t n) {
  static std::int64_t cached_n = -1;
  static std::unique_ptr<M> cached;
  if (cached_n != n) {
    cached.reset();
    cached = std::make_unique<M>();
    for (const Landmark& lm : make_landmark_field(n)) cached->insert(lm);
    cached_n = n;
  }
  return *cached;
}

// Updated landmarks for random ids, precomputed so the loop times only the map.
std::vector<Landmark> updates(const std::vector<Landmark>& field, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::vector<Landmark> out(count);
  for (Landmark& lm : out) {
    lm = field[rng() % field.size()];
    lm.mean += Vec2(0.01, -0.02);
    lm.log_odds += 0.5f;
  }
  return out;
}

// One set on a copy of the parent: the FastSLAM case (a resampled particle updates a landmark it shares).
// The time includes the O(1) copy and freeing the previous iteration's path, i.e. the steady-state cost.
template <class M>
void BM_Map_Set(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const M& parent = parent_map<M>(n);
  const auto ups = updates(make_landmark_field(n), kPrecomputed, 1);
  M child = parent;
  std::size_t i = 0;
  for (auto _ : state) {
    child = parent;
    child.set(ups[i++ % kPrecomputed]);
    benchmark::ClobberMemory();
  }
  // Bytes allocated by one set (outside the timed loop), where the back end counts them.
  if (live_bytes<M>() < 0) return;
  std::int64_t allocated = 0;
  for (int k = 0; k < 256; ++k) {
    M c = parent;
    const std::int64_t before = live_bytes<M>();
    c.set(ups[k]);
    allocated += live_bytes<M>() - before;
  }
  state.counters["alloc_bytes_per_set"] = static_cast<double>(allocated) / 256;
}

template <class M>
void BM_Map_Copy(benchmark::State& state) {
  const M& parent = parent_map<M>(state.range(0));
  for (auto _ : state) {
    M copy = parent;
    benchmark::DoNotOptimize(copy);
    benchmark::ClobberMemory();
  }
}

// A 30 x 30 m query (the sensor's reach) at random places in the field.
template <class M>
void BM_Map_VisitNear(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const M& parent = parent_map<M>(n);
  const double side = field_side_m(n);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-side / 2 + 15, side / 2 - 15);
  std::vector<Box2> boxes(kPrecomputed);
  for (Box2& b : boxes) {
    const Vec2 c = draw_vec2([&] { return u(rng); });
    b = Box2{c - Vec2(15, 15), c + Vec2(15, 15)};
  }
  std::size_t i = 0;
  std::int64_t found = 0;
  for (auto _ : state) {
    parent.visit_near(boxes[i++ % kPrecomputed], [&](const Landmark& lm) { found += lm.id >= 0; });
  }
  state.counters["results_per_query"] = static_cast<double>(found) / static_cast<double>(state.iterations());
}

// M particles copied from the parent, each updating kSetsPerParticle landmarks (one resampling generation).
// Counters: bytes per particle (parent's nodes amortised over M plus each particle's own), owned bytes per
// particle, bytes per landmark of the parent.
template <class M>
void BM_Map_Particles(benchmark::State& state) {
  const std::int64_t n = state.range(0);
  const M& parent = parent_map<M>(n);
  const auto ups = updates(make_landmark_field(n), kParticles * kSetsPerParticle, 2);
  std::vector<M> particles;
  for (auto _ : state) {
    particles.assign(kParticles, parent);
    for (int p = 0; p < kParticles; ++p)
      for (int k = 0; k < kSetsPerParticle; ++k) particles[p].set(ups[p * kSetsPerParticle + k]);
    benchmark::ClobberMemory();
  }
  double owned = 0;
  for (const M& p : particles) {
    const MapMemoryStats s = p.memory_stats();
    owned += static_cast<double>(s.bytes - s.shared_bytes);
  }
  const MapMemoryStats ps = parent.memory_stats();
  state.counters["owned_bytes_per_particle"] = owned / kParticles;
  state.counters["bytes_per_particle"] = (owned + static_cast<double>(ps.bytes)) / kParticles;
  state.counters["bytes_per_landmark"] = static_cast<double>(ps.bytes) / static_cast<double>(n);
}

// A filter's lineage: every step M particles are resampled (copies of random parents) and each sets
// kSetsPerStep landmarks in a window of 500 ids that moves 50 ids a step, as a robot's view does; 1000 steps.
// held_bytes_per_particle is what the population holds above the parent (live bytes): unlike memory_stats it
// includes what a node's base keeps alive (PersistentMapBase::derive), so back ends compare honestly.
template <class M>
void BM_Map_Lineage(benchmark::State& state) {
  constexpr int kSteps = 1000, kSetsPerStep = 20, kWindow = 500, kStride = 50;
  const std::int64_t n = state.range(0);
  const M& parent = parent_map<M>(n);
  const std::vector<Landmark> field = make_landmark_field(n);
  double held = 0;
  for (auto _ : state) {
    std::mt19937_64 rng(5);
    const std::int64_t before = live_bytes<M>();
    std::vector<M> particles(kParticles, parent), next(kParticles);
    for (int t = 0; t < kSteps; ++t) {
      for (M& p : next) p = particles[rng() % kParticles];
      std::swap(particles, next);
      const std::int64_t window = (std::int64_t{t} * kStride) % (n - kWindow);
      for (M& p : particles) {
        for (int k = 0; k < kSetsPerStep; ++k) {
          Landmark lm = field[window + static_cast<std::int64_t>(rng() % kWindow)];
          lm.mean += Vec2(1e-3 * static_cast<double>(rng() % 100), 0.0);
          p.set(lm);
        }
      }
    }
    next.clear();
    held = static_cast<double>(live_bytes<M>() - before);
    benchmark::ClobberMemory();
  }
  if (live_bytes<M>() >= 0) state.counters["held_bytes_per_particle"] = held / kParticles;
}

template <class M>
void register_backend() {
  const std::string name(M::kName);
  // N in the outer loop: benchmarks run in registration order, and parent_map keeps one N, so every kind
  // at one N shares a single build of the parent (building 10^6 landmarks costs seconds).
  // M full copies of the naive map at 10^6 would need 9.6 GB: its particle figures stop at 10^5.
  for (std::int64_t n = 100; n <= bench_max_n(); n *= 10) {
    if (name == "naive" && n > 1000000) break;  // M naive copies stop at 10^5 already; one set costs O(N)
    auto add = [&](const char* what, void (*fn)(benchmark::State&)) {
      return benchmark::RegisterBenchmark((std::string(what) + "/backend:" + name).c_str(), fn)->ArgName("n")->Arg(n);
    };
    add("BM_Map_Set", BM_Map_Set<M>);
    add("BM_Map_Copy", BM_Map_Copy<M>);
    add("BM_Map_VisitNear", BM_Map_VisitNear<M>);
    if (name != "naive" || n <= 100000) add("BM_Map_Particles", BM_Map_Particles<M>)->Unit(benchmark::kMicrosecond);
    if (n == 100000 && name != "naive") add("BM_Map_Lineage", BM_Map_Lineage<M>)->Unit(benchmark::kMillisecond)->Iterations(1);
  }
}

}  // namespace
}  // namespace arbor::bench

template <class... Maps>
void register_all(arbor::TypeList<Maps...>) {
  (arbor::bench::register_backend<Maps>(), ...);
}

int main(int argc, char** argv) {
  register_all(arbor::MapBackends{});
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
