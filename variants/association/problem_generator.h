// Random association problems with known true pairings: a uniform world of n landmarks at constant density,
// a robot in its middle seeing its m nearest landmarks plus clutter, a noisy pose prior and noisy landmark
// estimates, all drawn so that the problem's covariances are the true ones (a consistent problem).
#ifndef ARBOR_VARIANTS_ASSOCIATION_PROBLEM_GENERATOR_H_
#define ARBOR_VARIANTS_ASSOCIATION_PROBLEM_GENERATOR_H_

#include <cstdint>
#include <limits>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/pose2.h"
#include "core/metrics/association_score.h"

namespace arbor {

struct ProblemGeneratorOptions {
  int landmarks = 200;            // n: all of them are candidates
  int observations = 20;          // m true observations (of the m landmarks nearest the robot)
  int clutter = 5;                // spurious measurements, uniform in the disk the observations span
  std::uint64_t seed = 1;
  double density = 0.02;          // landmarks per m^2: the world's side grows as sqrt(n / density)
  double range_sigma = 0.1;       // R = diag(range_sigma^2, bearing_sigma^2)
  double bearing_sigma = 0.0175;  // ~1 degree
  Vec3 pose_sigma{0.3, 0.3, 0.05};  // P = diag(pose_sigma^2): x [m], y [m], theta [rad]
  double landmark_sigma_min = 0.05;  // each Sigma_j has principal std devs uniform in [min, max] [m]
  double landmark_sigma_max = 0.3;
  int locality = LocalitySet::kCapacity;  // each landmark's locality: its `locality` nearest neighbours
  double signature_sigma = std::numeric_limits<double>::quiet_NaN();  // finite: add signatures
};

struct GeneratedProblem {
  AssociationProblem problem;
  std::vector<LandmarkId> truth;  // per measurement: the true landmark id, or -1 for clutter
  Pose2 true_pose;
  Pose2 prior_pose;               // the pose the predictions were made from
  std::vector<Vec2> true_landmarks;  // indexed by id
};

// Deterministic for a given seed and build (std::normal_distribution is not specified bit-exactly).
// Requires 0 <= observations <= landmarks.
GeneratedProblem generate_association_problem(const ProblemGeneratorOptions& options);

// Fills each candidate's locality with its k nearest other candidates by position (a grid, O(n k)): the
// distance proxy for covisibility used where no scan history exists (generated and file problems).
void assign_nearest_localities(AssociationProblem* problem, int k);

// Scores one answer of a standalone problem against its truth (-1 = clutter), with the counts of
// core/metrics/association_score.h: a pairing with the true id is a true match, any other pairing (or a
// paired clutter measurement) a false match; an unpaired view of a candidate is a missed match, and a false
// new landmark too when it was declared NEW.
AssociationCounts score_against_truth(const std::vector<LandmarkId>& pairing, const std::vector<LandmarkId>& truth);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_PROBLEM_GENERATOR_H_
