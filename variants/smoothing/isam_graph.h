// Reader for the pre-associated iSAM/GTSAM 2-D text format (the Victoria Park file of GTSAM's examples):
//   ODOMETRY i j dx dy dtheta  c_xx c_xy c_xt c_yy c_yt c_tt   relative pose of j in i's frame, covariance
//   LANDMARK i l x y  c_xx c_xy c_yy                             landmark l in pose i's frame, covariance
// Pose and landmark ids share one integer space. The 6- and 3-tuples are read as the upper triangle of a
// covariance, as GTSAM's loader does for this file (data/victoria_park/SOURCE.md).
// Temporary: the data helper's experiments/loaders/isam_victoria_park.h is the intended loader; once it
// lands this file should become a thin adapter from its records to a FactorGraph.
#ifndef ARBOR_VARIANTS_SMOOTHING_ISAM_GRAPH_H_
#define ARBOR_VARIANTS_SMOOTHING_ISAM_GRAPH_H_

#include <string>

#include "variants/smoothing/factor_graph.h"

namespace arbor {

// Poses ordered by id (GraphPose::source_id keeps it; time_s is the pose's index, the file has no times),
// landmarks in order of first sighting. Initial values: odometry composed outwards from the lowest pose id
// (breadth first), landmarks from their first observation. A prior with standard deviation prior_sigma
// (m, m, rad) on the lowest pose at the origin fixes the gauge. Throws InputError on malformed lines, ids
// used as both pose and landmark, covariances that are not positive definite, and poses that odometry
// does not connect to the first.
FactorGraph read_isam_graph(const std::string& path, double prior_sigma = 1e-6);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_SMOOTHING_ISAM_GRAPH_H_
