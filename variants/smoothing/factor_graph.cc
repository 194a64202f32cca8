// Scenario + associations -> factor graph. Which poses become variables, and how the controls between them
// become one relative-motion factor each.
//
// Pose choice: a variable at the start and at every step that has a scan, a ground-truth pose, or is the
// last step. The steps in between carry no other factor, so eliminating them leaves one factor between
// the kept neighbours whose mean is the composition of the controls and whose covariance is propagated to
// first order; this is what linearised elimination of those poses would give, at a fraction of the size
// (Victoria Park: 61,945 controls but 7,249 scans).
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <fmt/core.h>

#include "core/io/input_error.h"
#include "core/models/range_bearing_model.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

// Rotates the translation part of a pose covariance from the frame of `from` into the frame of `delta`,
// where BetweenFactor measures its error: e_t = R(delta_th)^T (...).
Mat3 covariance_in_delta_frame(const Mat3& P, double delta_theta) {
  const double c = std::cos(delta_theta), s = std::sin(delta_theta);
  Mat3 G;
  G << c, s, 0, -s, c, 0, 0, 0, 1;
  Mat3 out = G * P * G.transpose();
  return 0.5 * (out + out.transpose());
}

// The pose of `trajectory` nearest in time to t (trajectory sorted by time, not empty).
Pose2 nearest_in_time(const std::vector<std::pair<double, Pose2>>& trajectory, double t) {
  auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                             [](const std::pair<double, Pose2>& a, double time) { return a.first < time; });
  if (it == trajectory.end()) return trajectory.back().second;
  if (it == trajectory.begin()) return it->second;
  auto prev = std::prev(it);
  return (t - prev->first <= it->first - t) ? prev->second : it->second;
}

}  // namespace

GraphValues initial_values(const FactorGraph& graph) {
  GraphValues values;
  values.poses.reserve(graph.poses.size());
  for (const GraphPose& p : graph.poses) values.poses.push_back(p.initial);
  values.landmarks.reserve(graph.landmarks.size());
  for (const GraphLandmark& l : graph.landmarks) values.landmarks.push_back(l.initial);
  return values;
}

SmootherAssociations SmootherAssociations::from_truth(const Scenario& scenario) {
  SmootherAssociations a;
  a.source = "known";
  a.landmark_ids.resize(scenario.steps.size());
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    for (const Measurement& m : scenario.steps[k].measurements)
      a.landmark_ids[k].push_back(m.truth_id >= 0 ? m.truth_id : kUnassociated);
  }
  return a;
}

std::size_t SmootherAssociations::associated_count() const {
  std::size_t n = 0;
  for (const auto& step : landmark_ids)
    n += std::count_if(step.begin(), step.end(), [](std::int64_t id) { return id != kUnassociated; });
  return n;
}

FactorGraph build_factor_graph(const Scenario& scenario, const SmootherAssociations& associations,
                               const SmootherOptions& options, const SmootherInitialGuess* guess) {
  if (associations.landmark_ids.size() != scenario.steps.size())
    throw InputError(associations.source, 0, "associations",
                     fmt::format("associations cover {} steps, the scenario has {}", associations.landmark_ids.size(),
                                 scenario.steps.size()));
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    if (associations.landmark_ids[k].size() != scenario.steps[k].measurements.size())
      throw InputError(associations.source, 0, "associations",
                       fmt::format("step {}: {} association decisions for {} measurements", k,
                                   associations.landmark_ids[k].size(), scenario.steps[k].measurements.size()));
  }

  FactorGraph graph;
  const MotionModel& motion = scenario.motion;
  graph.poses.push_back({scenario.start_time_s, -1, 0, scenario.initial_pose});
  PosePriorFactor prior;
  prior.pose = 0;
  prior.mean = scenario.initial_pose;
  prior.covariance = scenario.initial_sigma.cwiseMax(options.prior_floor_sigma).cwiseAbs2().asDiagonal();
  graph.priors.push_back(prior);

  // Chain the controls since the last kept pose: rel = prev^-1 * current, P its covariance (in prev's frame).
  // Every motion model is invariant to rigid motions of the start pose, so applying a control to rel gives
  // rel composed with the control's own motion.
  Pose2 rel;
  Mat3 P = Mat3::Zero();
  Pose2 dead_reckoning = scenario.initial_pose;
  double previous_time_s = scenario.start_time_s;
  for (std::size_t k = 0; k < scenario.steps.size(); ++k) {
    const ScenarioStep& step = scenario.steps[k];
    motion.predict(&rel, &P, step.control, step.time_s - previous_time_s);
    previous_time_s = step.time_s;
    const bool keep = step.has_scan || !step.measurements.empty() || (options.pose_at_truth_steps && step.truth_pose) ||
                      k + 1 == scenario.steps.size();
    if (!keep) continue;
    BetweenFactor between;
    between.from = static_cast<int>(graph.poses.size()) - 1;
    between.to = between.from + 1;
    between.delta = rel;
    between.covariance = covariance_in_delta_frame(P, rel.theta);
    between.covariance.diagonal() += options.motion_floor_variance;
    graph.betweens.push_back(between);
    dead_reckoning = dead_reckoning.compose(rel);
    graph.poses.push_back({step.time_s, static_cast<int>(k), static_cast<std::int64_t>(graph.poses.size()),
                           dead_reckoning});
    rel = Pose2{};
    P.setZero();
  }

  if (guess != nullptr && !guess->trajectory.empty()) {
    for (GraphPose& p : graph.poses) p.initial = nearest_in_time(guess->trajectory, p.time_s);
  }

  // Landmarks in order of first sighting; initialised from the guess or by inverting the first measurement.
  std::unordered_map<std::int64_t, int> landmark_index;
  const Mat2 R = scenario.sensor.R();
  for (std::size_t i = 1; i < graph.poses.size(); ++i) {
    const int k = graph.poses[i].step;
    const ScenarioStep& step = scenario.steps[k];
    for (std::size_t j = 0; j < step.measurements.size(); ++j) {
      const std::int64_t id = associations.landmark_ids[k][j];
      if (id == kUnassociated) continue;
      if (id < 0)
        throw InputError(associations.source, 0, "associations",
                         fmt::format("step {} measurement {}: landmark id {} is negative", k, j, id));
      const Vec2 z = step.measurements[j].z();
      auto [it, inserted] = landmark_index.try_emplace(id, static_cast<int>(graph.landmarks.size()));
      if (inserted) {
        GraphLandmark lm;
        lm.id = id;
        lm.initial = range_bearing_inverse(graph.poses[i].initial, z);
        if (guess != nullptr) {
          if (auto g = guess->landmarks.find(id); g != guess->landmarks.end()) lm.initial = g->second;
        }
        graph.landmarks.push_back(lm);
      }
      graph.range_bearings.push_back({static_cast<int>(i), it->second, z, R});
    }
  }
  return graph;
}

}  // namespace arbor
