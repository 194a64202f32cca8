// The standalone data-association problem (DESIGN.md §4): a strategy can be called, tested and benchmarked
// without a filter. The engine builds one per particle per scan; `arbor associate` reads one from a file.
#ifndef ARBOR_CORE_ASSOCIATION_ASSOCIATION_PROBLEM_H_
#define ARBOR_CORE_ASSOCIATION_ASSOCIATION_PROBLEM_H_

#include <cmath>
#include <concepts>
#include <cstdint>
#include <limits>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "core/types/landmark.h"
#include "core/math/eigen_types.h"

namespace arbor {

// Decisions other than a landmark id.
inline constexpr LandmarkId kNewLandmark = -1;  // start a new (provisional) landmark
inline constexpr LandmarkId kSpurious = -2;     // clutter: neither paired nor used to start a landmark

struct AssociationMeasurement {
  Vec2 z;  // (range [m], bearing [rad]) in the robot frame
  float signature = std::numeric_limits<float>::quiet_NaN();
  std::int32_t truth_id = -2;  // the scenario's ground-truth id (-1 clutter, -2 unknown); only `known` reads it
};

// A landmark that may have produced some of the measurements, with everything its prediction needs.
struct AssociationCandidate {
  LandmarkId id = kNoLandmark;
  Vec2 z_hat;           // predicted measurement h(x, m_j)
  Mat2 S;               // individual innovation covariance H_j Sigma_j H_j^T + R (pose part excluded)
  Mat23 H_pose;         // d h / d pose: couples candidates through the pose covariance P
  Vec2 position;        // landmark mean in the world frame (pose-free strategies use it)
  Mat2 position_cov;    // Sigma_j
  float signature = std::numeric_limits<float>::quiet_NaN();
  LocalitySet locality;
  std::int32_t truth_label = -1;  // Landmark::truth_label; only `known` reads it
};

struct AssociationProblem {
  std::vector<AssociationMeasurement> measurements;
  std::vector<AssociationCandidate> candidates;  // ascending id
  Mat2 R = Mat2::Identity();                     // measurement noise
  Mat3 P = Mat3::Zero();                         // pose covariance: zero for a sampled pose (FastSLAM 1.0)
  double signature_sigma = std::numeric_limits<double>::quiet_NaN();  // NaN: signatures are not compared
  // Optional: the joint covariance of all predicted measurements (2N x 2N, R on the diagonal blocks), as
  // given by the exchange format. When non-empty it replaces S, H_pose and P.
  Eigen::MatrixXd joint_covariance;

  // Covariance between the innovations of candidates i and j (2x2): S_i + H_i P H_i^T on the diagonal,
  // H_i P H_j^T off it.
  Mat2 innovation_covariance(int i, int j) const {
    if (joint_covariance.size() > 0) return joint_covariance.block<2, 2>(2 * i, 2 * j);
    Mat2 block = candidates[i].H_pose * P * candidates[j].H_pose.transpose();
    if (i == j) block += candidates[i].S;
    return block;
  }
};

struct AssociationStats {
  std::int64_t hypotheses = 0;  // search-tree nodes visited
  std::int64_t tests = 0;       // compatibility tests run
  // True when a tree search stopped at AssociationOptions::max_hypotheses or max_work: the answer is the best
  // found so far (still jointly compatible), not necessarily the optimum.
  bool budget_exhausted = false;
  std::int64_t rejected = 0;  // known association: pairings its gate refused
};

struct AssociationResult {
  std::vector<LandmarkId> pairing;  // one per measurement: a candidate id, kNewLandmark or kSpurious
  AssociationStats stats;
};

// Options shared by the strategies; each reads what it needs.
struct AssociationOptions {
  double gate_probability = 0.99;    // chi-square gate, individual and joint
  double new_landmark_probability = 0.999;  // outside this gate of every candidate a measurement starts a landmark
  int locality_capacity = LocalitySet::kCapacity;
  std::int64_t max_hypotheses = 1'000'000;  // search budget for the tree searches: nodes
  // ... and their work, in elementary operations (a multiply-add of JCBB's factor update, a candidate scanned;
  // a tree search's compatibility test counts kTreeTestWork): nodes alone did not bound the time where a node
  // costs O(m^2), as JCBB's Cholesky form does (a 1 MB exchange-format problem, m = 200, ran 28 s). About a
  // second of search; in the filter the node budget binds first.
  std::int64_t max_work = std::int64_t{1} << 30;
  // Known association trusts the ids, not the measurements: a pairing whose innovation lies outside this
  // chi-square gate (2 dof, pose and landmark uncertainty included) is refused and counted. 1: no gate, the
  // default: known association is the oracle, and a particle's own covariance cannot hold the drift of a gap
  // between sightings, so a gate there refused the truth for good once a particle had drifted (issue 41:
  // 3,102 true measurements on one held-out UTIAS robot).
  double known_gate_probability = 1.0;
  // Pose-free tree search (relocalisation): stop at the first verified pose whose completion explains at least
  // this fraction of the scan's measurements (and at least 3 of them), like a relocaliser that accepts the
  // first pose with enough inliers. 0: search to the bound, then pick the best of the ranked poses.
  double accept_explained = 0.0;
  // Pose-free tree search: when the winner explains less than this fraction of the scan and the ranking of
  // verified hypotheses cut the search short, search again keeping kTreeWideningFactor times as many
  // (variants/association/tree_search.h gives the figures). 0: never.
  double widen_below = 0.5;
  // Pose-free tree search: pair the whole scan again at each verified pose, gated with that pose's fitted
  // covariance, and keep that answer where it pairs as many and passes the joint test.
  bool pair_again_at_pose = true;
};

// What a strategy is and promises. The one strategy list (variants/association/strategy_list.h) is filtered
// by these: the CLI's choices, the engine instantiations, the benchmarks and the conformance suite
// (tests/association/strategy_conformance_test.cc, which checks every promise made here).
struct StrategyTraits {
  // Pairs by the measurements' truth ids and the candidates' truth labels (known association): the engine
  // shows it every landmark in the query box (an id must find its landmark wherever the estimate put it)
  // and does not prune by existence evidence (the ids say what exists).
  bool uses_ground_truth = false;
  bool in_filter = true;    // offered per particle by `arbor run`
  bool standalone = true;   // offered by `arbor associate`, `arbor relocalize` and the benchmarks
  bool mutually_exclusive = true;  // never pairs two measurements of one scan with one landmark
  // Every answer passes the joint chi-square test with the problem's own predictions (pose part included).
  bool jointly_compatible = false;
  // stats.hypotheses never exceeds the locality bound n((c+1)^m - 1)/c + 1 (DESIGN.md §4).
  bool locality_bound = false;
  // Reads the candidates' locality (covisibility) sets. In the filter the engine keeps the sets only for a
  // strategy that does (or for --relocalize); any other strategy sees them empty.
  bool reads_localities = false;
};

// The AssociationStrategy concept. Strategies are stateless apart from their options; solve() is called
// concurrently from many particles, each thread with its own Scratch.
//   A a(options);  typename A::Scratch s;  a.solve(problem, s, result);  A::kName  A::kTraits
template <class A>
concept AssociationStrategy = std::constructible_from<A, const AssociationOptions&> &&
    std::default_initializable<typename A::Scratch> &&
    requires(const A a, const AssociationProblem& p, typename A::Scratch& s, AssociationResult& r) {
      a.solve(p, s, r);
      { A::kName } -> std::convertible_to<std::string_view>;
      { A::kTraits } -> std::convertible_to<StrategyTraits>;
    };

}  // namespace arbor

#endif  // ARBOR_CORE_ASSOCIATION_ASSOCIATION_PROBLEM_H_
