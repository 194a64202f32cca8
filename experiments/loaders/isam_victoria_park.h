// The iSAM/GTSAM Victoria Park file (pre-associated; GTSAM examples/Data/victoria_park.txt): a pose chain with
// relative-pose odometry and landmark observations with ids, the input of the smoothing baseline. Facts and
// the covariance convention (GTSAM reads the 6-tuple as covariance): data/victoria_park/SOURCE.md.
#ifndef ARBOR_EXPERIMENTS_LOADERS_ISAM_VICTORIA_PARK_H_
#define ARBOR_EXPERIMENTS_LOADERS_ISAM_VICTORIA_PARK_H_

#include <cstdint>
#include <string>
#include <vector>

#include "core/types/scenario.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"

namespace arbor {

// `ODOMETRY i j dx dy dtheta c_xx c_xy c_xt c_yy c_yt c_tt`: pose j relative to pose i.
struct IsamOdometry {
  std::int64_t from = 0, to = 0;
  Pose2 delta;      // pose `to` in the frame of pose `from`
  Mat3 covariance;  // of (dx, dy, dtheta)
};

// `LANDMARK i l x y c_xx c_xy c_yy`: landmark l at (x ahead, y left) in the frame of pose i.
struct IsamObservation {
  std::int64_t pose = 0, landmark = 0;
  Vec2 position_m = Vec2::Zero();
  Mat2 covariance;
};

// Pose and landmark ids share one integer space. pose_ids is the chain in order (the first is the origin
// pose, which the file never states); odometry[k] links pose_ids[k] to pose_ids[k + 1].
struct IsamDataset {
  std::vector<std::int64_t> pose_ids;
  std::vector<IsamOdometry> odometry;
  std::vector<IsamObservation> observations;  // in file order
  std::vector<std::int64_t> landmark_ids;     // sorted, unique
};

// Throws InputError naming file, line and field on malformed lines, a broken pose chain (odometry not
// starting at the last pose, an id used twice), observations from unknown poses, landmark ids that are pose
// ids, and covariances that are not positive definite.
IsamDataset read_isam_dataset(const std::string& path);

// As a scenario (so `arbor run` can use it): the odometry model with u = (rot1, trans, rot2) from each
// relative pose, one step per odometry line at time_s = pose index (the file has no time stamps), the
// observations as range-bearing scans with the landmark ids as truth ids. Noise: the file's observation
// covariance as sigma_range = sqrt(c_xx) and sigma_bearing = sqrt(c_yy) / median range; odometry alphas are
// tuning defaults (docs/datasets.md).
Scenario isam_to_scenario(const IsamDataset& dataset, const std::string& source_path = "");

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_ISAM_VICTORIA_PARK_H_
