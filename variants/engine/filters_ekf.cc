// EKF-SLAM (core/engine/ekf_slam.h) behind the Filter interface, for every strategy usable in the filter. It
// has no particles and no map back end: its one estimate is reported as a single particle of weight 1, and
// the landmarks' records sit in the naive back end, which only the shared gathering and existence code read.
#include <fmt/format.h>

#include "core/engine/ekf_slam.h"
#include "variants/registry.h"

namespace arbor {
namespace {

template <AssociationStrategy Assoc>
class EkfFilter final : public Filter {
 public:
  EkfFilter(const Scenario& scenario, const FastSlamOptions& options) : engine_(scenario, options) {}

  void step(const ScenarioStep& step) override { engine_.step(step); }
  void set_prior_map(const std::vector<Landmark>& landmarks) override { engine_.set_prior_map(landmarks); }
  const StepStats& last_step_stats() const override { return engine_.last_step_stats(); }
  PoseEstimate estimate() const override { return engine_.estimate(); }
  std::vector<WeightedPose> particles() const override { return {{engine_.estimate().mean, 1.0}}; }
  std::vector<TimedPose> best_trajectory() const override { return engine_.history().to_vector(); }
  std::vector<Landmark> best_map() const override {
    std::vector<Landmark> out;
    engine_.map().for_each([&](const Landmark& lm) { out.push_back(lm); });
    return out;
  }
  std::int64_t best_rejected_measurements() const override { return engine_.rejected(); }
  std::int64_t best_loop_closures() const override { return 0; }
  std::vector<StepDecisions> best_decisions() const override { return engine_.decisions().to_vector(); }
  std::int64_t relocalizations() const override { return 0; }
  std::optional<double> common_ancestor_time_s() const override { return std::nullopt; }
  // The joint Gaussian (the covariance's allocated capacity) and the landmarks' records.
  MapMemoryStats memory_stats() const override {
    MapMemoryStats stats = engine_.map().memory_stats();
    stats.add(1, engine_.state().bytes(), false);
    return stats;
  }
  std::string map_name() const override { return "none"; }
  std::string association_name() const override { return std::string(Assoc::kName); }

 private:
  EkfSlam<VectorMap, Assoc> engine_;
};

}  // namespace

std::unique_ptr<Filter> make_ekf_filter(std::string_view assoc, const Scenario& scenario, const FastSlamOptions& options) {
  return make_for_strategy(AssociationStrategies{}, assoc, [&]<class S>() -> std::unique_ptr<Filter> {
    return std::make_unique<EkfFilter<S>>(scenario, options);
  });
}

}  // namespace arbor
