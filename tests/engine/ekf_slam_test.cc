// EKF-SLAM (core/engine/ekf_slam.h): a joint covariance that stays symmetric positive definite through a long
// cluttered run, a state that holds exactly the landmarks the map reports, consistency on simulated worlds,
// the oracle refusing nothing, a prior map it localises in, and runs that do not depend on the thread count.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>

#include "core/engine/ekf_slam.h"
#include "core/io/trajectory_io.h"
#include "core/metrics/run_statistics.h"
#include "core/metrics/trajectory_metrics.h"
#include "tests/engine/worlds.h"
#include "variants/association/jcbb.h"
#include "variants/association/known_association.h"
#include "variants/maps/vector_map.h"

namespace arbor {
namespace {

RunConfig ekf_config(const std::string& assoc) {
  RunConfig c;
  c.options.version = FilterVersion::kEkf;
  c.assoc = assoc;
  return c;
}

// Checked after every step, not only at the end: a covariance that loses definiteness for one scan and
// regains it would still have gated that scan wrongly.
template <AssociationStrategy Assoc>
void expect_positive_definite_throughout(const Scenario& s) {
  FastSlamOptions options;
  options.version = FilterVersion::kEkf;
  EkfSlam<VectorMap, Assoc> ekf(s, options);
  int checked = 0, semidefinite = 0;
  std::size_t most_landmarks = 0;
  for (std::size_t k = 0; k < s.steps.size(); ++k) {
    ekf.step(s.steps[k]);
    if (!s.steps[k].has_scan) continue;
    const Eigen::MatrixXd P = ekf.state().covariance();
    ASSERT_EQ(P.rows(), 3 + 2 * static_cast<int>(ekf.map().size())) << "step " << k;
    ASSERT_TRUE(P.isApprox(P.transpose(), 0.0)) << "not symmetric at step " << k;
    // The start pose is exact and the first controls' noise tiny and nearly rank 1 (along the track), so at
    // first the pose block is (numerically) singular and the joint covariance only semidefinite; once the pose block is
    // definite the whole must be, with room to spare: the smallest eigenvalue is not lost to rounding.
    const Eigen::VectorXd eigenvalues = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(P).eigenvalues();
    const double largest = eigenvalues(eigenvalues.size() - 1);
    const Vec3 pose_eigenvalues = Eigen::SelfAdjointEigenSolver<Mat3>(ekf.state().pose_covariance()).eigenvalues();
    if (pose_eigenvalues(2) < 1e-8 || pose_eigenvalues(0) <= 1e-9 * pose_eigenvalues(2)) {
      ++semidefinite;
      ASSERT_GE(eigenvalues(0), -1e-12 * largest) << "not semidefinite at step " << k;
      continue;
    }
    ASSERT_EQ(Eigen::LLT<Eigen::MatrixXd>(P).info(), Eigen::Success) << "not positive definite at step " << k;
    ASSERT_GT(eigenvalues(0), 1e-12 * largest) << "step " << k;
    most_landmarks = std::max(most_landmarks, ekf.map().size());
    ++checked;
  }
  EXPECT_GT(checked, 290);
  EXPECT_LT(semidefinite, 5);
  EXPECT_GT(most_landmarks, 40u);  // the check ran over a map that grew, and pruned what the clutter started
}

TEST(EkfSlam, JointCovarianceStaysSymmetricPositiveDefiniteOverALongClutteredRun) {
  const Scenario s = testing::cluttered_rooms(4, 150, 2.0, 300);
  expect_positive_definite_throughout<Jcbb>(s);
  expect_positive_definite_throughout<KnownAssociation>(s);
}

// The oracle refuses no true measurement (no gate by default), and pairs every one: F1 = 1.
TEST(EkfSlam, KnownAssociationRefusesNothingOnASimulatedWorld) {
  const RunOutput out = run_fastslam(testing::simulated_world(2, 200), ekf_config("known"));
  EXPECT_EQ(out.result["rejected_measurements"], 0);
  EXPECT_EQ(out.result["assoc_f1"], 1.0);
}

// Over several worlds the pose NEES (3 dof) is consistent: its median near chi-square(3)'s 2.37 and most
// scans inside the 95 % band. An EKF without the pose part of the landmarks' initial covariance, or with the
// cross terms left out of the prediction, is overconfident by an order of magnitude here.
TEST(EkfSlam, PoseNeesIsConsistentOnSimulatedWorlds) {
  std::vector<double> nees;
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    const RunOutput out = run_fastslam(testing::simulated_world(seed, 200), ekf_config("known"));
    nees.insert(nees.end(), out.nees.begin(), out.nees.end());
  }
  ASSERT_GT(nees.size(), 900u);
  EXPECT_GT(quantile(nees, 0.5), 0.5);
  EXPECT_LT(quantile(nees, 0.5), 5.0);
  EXPECT_GT(fraction_in_band(nees, kNeesBand3Dof95), 0.8);
}

// Localisation in a surveyed map: every landmark known from the start, the pose stays on the truth.
TEST(EkfSlam, LocalisesInAPriorMap) {
  const Scenario s = testing::simulated_world(6, 150);
  const std::string survey = testing::scratch_dir("ekf_prior") + "/map.csv";
  std::vector<Landmark> map;
  for (const TruthLandmark& t : s.truth_landmarks) {
    Landmark lm;
    lm.id = t.id;
    lm.truth_label = t.id;
    lm.mean = t.position;
    lm.cov = Mat2::Identity() * 1e-4;
    map.push_back(lm);
  }
  write_map_csv(survey, map);
  RunConfig c = ekf_config("known");
  c.prior_map_path = survey;
  const RunOutput out = run_fastslam(s, c);
  EXPECT_LT(out.result["ate_rmse_m"].get<double>(), 0.1);
  EXPECT_EQ(out.result["assoc_f1"], 1.0);
}

// Serial by construction; the run still takes --threads, and must not depend on it.
TEST(EkfSlam, RunIsIdenticalWithOneAndTwoThreads) {
  const Scenario s = testing::cluttered_rooms(2, 120, 2.0, 150);
  std::string reference;
  for (int threads : {1, 2}) {
    RunConfig c = ekf_config("jcbb");
    c.options.threads = threads;
    c.out_dir = testing::scratch_dir("ekf_threads_" + std::to_string(threads));
    run_fastslam(s, c);
    const std::string files = testing::read_file(c.out_dir + "/trajectory.tum") + testing::read_file(c.out_dir + "/map.csv");
    if (reference.empty()) reference = files;
    EXPECT_TRUE(files == reference) << threads << " threads";
  }
}

}  // namespace
}  // namespace arbor
