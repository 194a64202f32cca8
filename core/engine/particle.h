// What a FastSLAM particle carries between steps, and what one step reports (core/engine/fastslam.h).
#ifndef ARBOR_CORE_ENGINE_PARTICLE_H_
#define ARBOR_CORE_ENGINE_PARTICLE_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <vector>

#include "core/check.h"
#include "core/engine/loop_closing.h"
#include "core/engine/map_concept.h"
#include "core/engine/persistent_history.h"
#include "core/engine/resample_move.h"
#include "core/engine/rng.h"
#include "core/math/eigen_types.h"
#include "core/math/angles.h"
#include "core/math/pose2.h"
#include "core/types/scenario.h"

namespace arbor {

template <LandmarkMap Map>
struct Particle {
  Pose2 pose;                   // the last draw, or between draws the predicted mean since it
  Mat3 pose_covariance = Mat3::Zero();  // of the prediction since the last draw (zero right after one)
  double log_weight = 0.0;
  Map map;
  PoseHistory history;
  DecisionHistory decisions;    // scans with measurements or removals; for scoring and `arbor smooth --associations`
  LandmarkId next_id = 0;       // the next new landmark's id (creation order, the same in every back end)
  std::int64_t rejected = 0;    // this lineage's measurements rejected by the known-association gate
  // Loop closing's lineage state (core/engine/loop_closing.h): it is resampled with the map it refers to.
  std::vector<LandmarkAlias> aliases;  // open loop closures, oldest first (FastSlamOptions::close_loops)
  std::int64_t loop_closures = 0;      // aliases this lineage made
  MoveWindow move;                     // its last scans, for resample-move (FastSlamOptions::move_window)
};

// Particle index's start: a draw from the scenario's initial pose and its spread, from the stream (seed, -1,
// index, kMotion), the first entry of its history and the anchor of its resample-move window.
template <LandmarkMap Map>
void start_particle(const Scenario& scenario, std::uint64_t seed, int index, Particle<Map>* particle) {
  RandomStream rng(seed, ~std::uint64_t{0}, index, RandomPurpose::kMotion);
  Pose2& pose = particle->pose;
  pose = scenario.initial_pose;
  pose.x += scenario.initial_sigma.x() * rng.normal();
  pose.y += scenario.initial_sigma.y() * rng.normal();
  pose.theta = wrap_angle(pose.theta + scenario.initial_sigma.z() * rng.normal());
  particle->history.push({scenario.start_time_s, pose});
  particle->move.anchor = pose;
}

// What one step did, summed over particles where it is a count.
struct StepStats {
  double n_eff = 0.0;       // effective sample size after weighting, before any resampling
  bool resampled = false;   // whether this step began by resampling
  std::int64_t hypotheses = 0;
  std::int64_t tests = 0;
  std::int64_t budget_exhausted = 0;  // particles whose search stopped at its budget (best answer so far)
  std::size_t best_landmarks = 0;
  bool relocalized = false;  // this scan re-seeded every particle at a relocalised pose
  std::int64_t moves_proposed = 0;  // resample-move proposals after this step's resampling
  std::int64_t moves_accepted = 0;
};

// Weighted mean and covariance of the particle poses (heading by circular mean, differences wrapped); between
// draws each particle is a Gaussian, whose covariance the mixture's adds.
struct PoseEstimate {
  Pose2 mean;
  Mat3 covariance = Mat3::Zero();
};

// Starts every particle from the same prior map: a map built before the run (the step benchmarks at up to
// 10^6 landmarks, relocalisation in a known map). The particles' copies share it, so for a persistent back end
// this costs O(M). New landmarks get ids above the prior's; with known association, a prior landmark's
// truth_label is the ground-truth id that refers to it. Prior landmarks are taken as they are: mark them
// confirmed, or an unknown-association filter will drop them as unconfirmed.
template <class Map, class Particle>
void start_from_prior_map(const Map& map, std::vector<Particle>* particles) {
  std::int64_t next = 0;
  map.for_each([&](const Landmark& lm) { next = std::max<std::int64_t>(next, std::int64_t{lm.id} + 1); });
  // The readers keep ids to 2^30 - 1 (core/io/field_limits.h), the largest included; the filter numbers its own
  // landmarks above, in [2^30, 2^31 - 1].
  ARBOR_CHECK(next - 1 <= std::numeric_limits<LandmarkId>::max() / 2, "prior map landmark id {} leaves no ids for new landmarks", next - 1);
  for (auto& p : *particles) {
    p.map = map;
    p.next_id = next;
  }
}

// One particle's predicted pose: its mean and the covariance of the controls since its last draw.
struct PosePrediction {
  Pose2 pose;
  Mat3 pose_covariance = Mat3::Zero();
};

// The set's PoseEstimate under weights (one per particle).
template <class Particle>
PoseEstimate weighted_pose_estimate(const std::vector<Particle>& particles, const std::vector<double>& weights) {
  PoseEstimate e;
  double x = 0.0, y = 0.0, s = 0.0, c = 0.0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Pose2& p = particles[i].pose;
    x += weights[i] * p.x;
    y += weights[i] * p.y;
    s += weights[i] * std::sin(p.theta);
    c += weights[i] * std::cos(p.theta);
  }
  e.mean = {x, y, std::atan2(s, c)};
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const Vec3 d = pose_error(particles[i].pose, e.mean);
    e.covariance += weights[i] * (d * d.transpose() + particles[i].pose_covariance);
  }
  return e;
}

// The time of the newest pose every particle's path shares: the set can revise nothing older (path
// degeneracy: Bailey, Nieto & Nebot 2006, "Consistency of the FastSLAM algorithm"; Doucet & Johansen 2011,
// "A tutorial on particle filtering and smoothing"). Empty while the paths share none.
template <class Particle>
std::optional<double> paths_meet_time_s(const std::vector<Particle>& particles) {
  std::vector<const PoseHistory*> histories;
  for (const Particle& p : particles) histories.push_back(&p.history);
  const TimedPose* shared = PoseHistory::newest_shared_entry(histories);
  return shared ? std::optional<double>(shared->time_s) : std::nullopt;
}

// The memory the particles' maps hold, each shared node counted once per map that reaches it.
template <class Particle>
MapMemoryStats summed_memory_stats(const std::vector<Particle>& particles) {
  MapMemoryStats total;
  for (const Particle& p : particles) total += p.map.memory_stats();
  return total;
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_PARTICLE_H_
