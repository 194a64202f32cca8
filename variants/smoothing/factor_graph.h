// The full-SLAM problem as a plain factor graph (no Ceres types): pose and landmark variables with initial
// values, and the factors between them. Built from a scenario or read from a pre-associated file; solved by
// ceres_smoother.cc and exported by g2o_writer.cc, so every consumer sees exactly the same problem.
#ifndef ARBOR_VARIANTS_SMOOTHING_FACTOR_GRAPH_H_
#define ARBOR_VARIANTS_SMOOTHING_FACTOR_GRAPH_H_

#include <cstdint>
#include <vector>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

// A pose variable. step: the scenario step whose end it marks, or -1 for the start pose (and for files
// that have no steps). source_id: the id in the file the graph came from (iSAM), else the pose's index.
struct GraphPose {
  double time_s = 0.0;
  int step = -1;
  std::int64_t source_id = 0;
  Pose2 initial;
};

// A point landmark variable; id is the association's landmark id (truth id, FastSLAM id, file id).
struct GraphLandmark {
  std::int64_t id = 0;
  Vec2 initial = Vec2::Zero();
};

// Relative motion from pose `from` to pose `to`. Error (as g2o's EdgeSE2):
//   e = t2v(delta^-1 * (from^-1 * to)),  i.e.  e_t = R(delta_th)^T (R(th_from)^T (p_to - p_from) - delta_t),
//   e_th = wrap(th_to - th_from - delta_th); covariance is of e (expressed in the frame of delta).
struct BetweenFactor {
  int from = 0;
  int to = 0;
  Pose2 delta;
  Mat3 covariance = Mat3::Identity();
};

// Range-bearing observation z = (r, phi) of a landmark (core/models/range_bearing_model.h), bearing wrapped.
struct RangeBearingFactor {
  int pose = 0;
  int landmark = 0;
  Vec2 z = Vec2::Zero();
  Mat2 covariance = Mat2::Identity();
};

// Cartesian observation of a landmark in the robot frame (x forward, y left): e = R(th)^T (m - p) - p_robot.
// The form of the pre-associated Victoria Park file (iSAM/GTSAM "LANDMARK" lines).
struct PointFactor {
  int pose = 0;
  int landmark = 0;
  Vec2 p_robot = Vec2::Zero();
  Mat2 covariance = Mat2::Identity();
};

// Absolute prior on a pose; fixes the gauge (the problem is otherwise invariant to a rigid motion).
struct PosePriorFactor {
  int pose = 0;
  Pose2 mean;
  Mat3 covariance = Mat3::Identity();
};

struct FactorGraph {
  std::vector<GraphPose> poses;
  std::vector<GraphLandmark> landmarks;
  std::vector<BetweenFactor> betweens;
  std::vector<RangeBearingFactor> range_bearings;
  std::vector<PointFactor> points;
  std::vector<PosePriorFactor> priors;

  std::size_t factor_count() const { return betweens.size() + range_bearings.size() + points.size() + priors.size(); }
};

// Values of every variable, indexed like FactorGraph::poses and ::landmarks.
struct GraphValues {
  std::vector<Pose2> poses;
  std::vector<Vec2> landmarks;
};

// The initial values stored in the graph.
GraphValues initial_values(const FactorGraph& graph);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_SMOOTHING_FACTOR_GRAPH_H_
