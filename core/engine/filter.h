// The run-time boundary: one virtual call per time step, never per particle. FilterImpl<Map, Assoc> wraps
// the templated engine; variants/registry.h builds one from the names given on the command line.
#ifndef ARBOR_CORE_ENGINE_FILTER_H_
#define ARBOR_CORE_ENGINE_FILTER_H_

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include "core/engine/fastslam.h"

namespace arbor {

struct WeightedPose {
  Pose2 pose;
  double weight = 0.0;
};

class Filter {
 public:
  virtual ~Filter() = default;
  virtual void step(const ScenarioStep& step) = 0;
  // Before the first step: every particle starts from this map (unique ids; FastSlam::set_prior_map).
  virtual void set_prior_map(const std::vector<Landmark>& landmarks) = 0;
  virtual const StepStats& last_step_stats() const = 0;
  virtual PoseEstimate estimate() const = 0;
  // Every particle's pose (between scans, the mean it predicts) and normalised weight, in particle order.
  virtual std::vector<WeightedPose> particles() const = 0;
  // The particle of highest weight: its trajectory (oldest first) and its map (ascending id).
  virtual std::vector<TimedPose> best_trajectory() const = 0;
  // The weighted mean of every particle's whole path under the final weights: the particle approximation of
  // the posterior mean E[x_1:T | z_1:T] (Doucet, Godsill & Andrieu 2000), where the best particle's path is
  // one sample of it. A filter with one estimate returns that estimate.
  virtual std::vector<TimedPose> path_mean_trajectory() const { return best_trajectory(); }
  virtual std::vector<Landmark> best_map() const = 0;
  // Measurements the known-association gate rejected in the best particle's lineage.
  virtual std::int64_t best_rejected_measurements() const = 0;
  // Loops the best particle's lineage closed by re-sighting (FastSlamOptions::close_loops).
  virtual std::int64_t best_loop_closures() const = 0;
  // The best particle's association decisions, one entry per scan with measurements or removals, oldest
  // first; core/metrics/decision_score.h scores them against ground truth.
  virtual std::vector<StepDecisions> best_decisions() const = 0;
  // The time of the newest pose all particles' paths share (FastSlam::common_ancestor_time_s); empty while
  // they share none, and for a filter without particles.
  virtual std::optional<double> common_ancestor_time_s() const = 0;
  // Scans at which the particles were re-seeded at a relocalised pose (FastSlamOptions::relocalize).
  virtual std::int64_t relocalizations() const = 0;
  // Summed over all particles; shared nodes are counted once per particle that references them.
  virtual MapMemoryStats memory_stats() const = 0;
  virtual std::string map_name() const = 0;
  virtual std::string association_name() const = 0;
};

template <LandmarkMap Map, AssociationStrategy Assoc>
class FilterImpl final : public Filter {
 public:
  FilterImpl(const Scenario& scenario, const FastSlamOptions& options, Relocalizer relocalizer = {})
      : engine_(scenario, options, std::move(relocalizer)) {}

  void step(const ScenarioStep& step) override { engine_.step(step); }
  void set_prior_map(const std::vector<Landmark>& landmarks) override {
    Map map;
    for (const Landmark& lm : landmarks) map.insert(lm);
    engine_.set_prior_map(map);
  }
  const StepStats& last_step_stats() const override { return engine_.last_step_stats(); }
  PoseEstimate estimate() const override { return engine_.estimate(); }
  std::vector<WeightedPose> particles() const override {
    std::vector<WeightedPose> out(engine_.particle_count());
    for (int i = 0; i < engine_.particle_count(); ++i) out[i] = {engine_.predicted_pose(i).pose, engine_.weight(i)};
    return out;
  }
  std::vector<TimedPose> best_trajectory() const override {
    return engine_.particle(engine_.best_particle()).history.to_vector();
  }
  std::vector<TimedPose> path_mean_trajectory() const override {
    std::vector<TimedPose> mean = engine_.particle(0).history.to_vector();
    std::vector<double> sin_sum(mean.size()), cos_sum(mean.size());
    for (TimedPose& p : mean) p.pose = Pose2{0.0, 0.0, 0.0};
    for (int i = 0; i < engine_.particle_count(); ++i) {
      const std::vector<TimedPose> path = engine_.particle(i).history.to_vector();
      if (path.size() != mean.size()) return best_trajectory();  // paths of different lengths: no common times
      const double w = engine_.weight(i);
      for (std::size_t k = 0; k < path.size(); ++k) {
        mean[k].pose.x += w * path[k].pose.x;
        mean[k].pose.y += w * path[k].pose.y;
        sin_sum[k] += w * std::sin(path[k].pose.theta);
        cos_sum[k] += w * std::cos(path[k].pose.theta);
      }
    }
    for (std::size_t k = 0; k < mean.size(); ++k) mean[k].pose.theta = std::atan2(sin_sum[k], cos_sum[k]);
    return mean;
  }
  // Without the copies that are aliases of older landmarks: they are bookkeeping of an open loop closure.
  std::vector<Landmark> best_map() const override {
    const auto& best = engine_.particle(engine_.best_particle());
    std::vector<Landmark> out;
    const auto is_copy = [&](const Landmark& lm) {
      const auto& aliases = best.aliases;
      return std::any_of(aliases.begin(), aliases.end(), [&](const LandmarkAlias& a) { return a.copy == lm.id; });
    };
    best.map.for_each([&](const Landmark& lm) {
      if (!is_copy(lm)) out.push_back(lm);
    });
    return out;
  }
  std::int64_t best_loop_closures() const override { return engine_.particle(engine_.best_particle()).loop_closures; }
  std::int64_t best_rejected_measurements() const override {
    return engine_.particle(engine_.best_particle()).rejected;
  }
  std::vector<StepDecisions> best_decisions() const override {
    return engine_.particle(engine_.best_particle()).decisions.to_vector();
  }
  std::int64_t relocalizations() const override { return engine_.relocalizations(); }
  std::optional<double> common_ancestor_time_s() const override { return engine_.common_ancestor_time_s(); }
  MapMemoryStats memory_stats() const override { return engine_.memory_stats(); }
  std::string map_name() const override { return std::string(Map::kName); }
  std::string association_name() const override { return std::string(Assoc::kName); }

  const FastSlam<Map, Assoc>& engine() const { return engine_; }

 private:
  FastSlam<Map, Assoc> engine_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_FILTER_H_
