// IsamDataset -> FactorGraph (see isam_factor_graph.h).
#ifdef ARBOR_HAVE_SMOOTHER
#include "experiments/loaders/isam_factor_graph.h"

#include <unordered_map>

namespace arbor {

FactorGraph isam_factor_graph(const IsamDataset& d, double prior_sigma) {
  FactorGraph graph;
  std::unordered_map<std::int64_t, int> pose_index, landmark_index;
  Pose2 dead_reckoning;
  for (std::size_t k = 0; k < d.pose_ids.size(); ++k) {
    if (k > 0) dead_reckoning = dead_reckoning.compose(d.odometry[k - 1].delta);
    pose_index[d.pose_ids[k]] = static_cast<int>(k);
    graph.poses.push_back({static_cast<double>(k), -1, d.pose_ids[k], dead_reckoning});
  }
  for (const IsamOdometry& o : d.odometry)
    graph.betweens.push_back({pose_index.at(o.from), pose_index.at(o.to), o.delta, o.covariance});
  for (const IsamObservation& ob : d.observations) {
    const int pose = pose_index.at(ob.pose);
    auto [it, inserted] = landmark_index.try_emplace(ob.landmark, static_cast<int>(graph.landmarks.size()));
    if (inserted) graph.landmarks.push_back({ob.landmark, graph.poses[pose].initial.transform(ob.position_m)});
    graph.points.push_back({pose, it->second, ob.position_m, ob.covariance});
  }
  graph.priors.push_back({0, Pose2{}, Mat3::Identity() * prior_sigma * prior_sigma});
  return graph;
}

}  // namespace arbor
#endif  // ARBOR_HAVE_SMOOTHER
