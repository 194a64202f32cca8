// Joint Compatibility Branch and Bound (Neira & Tardós 2001, IEEE T-RA 17(6)): the hypothesis with the most
// pairings whose joint innovation passes a chi-square test, the pose covariance's correlations included.
#ifndef ARBOR_VARIANTS_ASSOCIATION_JCBB_H_
#define ARBOR_VARIANTS_ASSOCIATION_JCBB_H_

#include <string_view>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "variants/association/association_common.h"
#include "variants/association/joint_information.h"

namespace arbor {

// Per-thread buffers; sized on demand, capacity only (never affects a result).
struct JcbbScratch {
  association::IndividualGating gating;
  std::vector<int> order;         // level k of the tree is measurement order[k] (canonical order, see solve)
  std::vector<int> list_begin;    // individually compatible candidates of level k: list[list_begin[k] ..)
  std::vector<int> list;          //   candidate indices sorted by (individual distance, id)
  std::vector<double> list_d2;
  std::vector<char> used;         // candidate taken by the current hypothesis
  std::vector<int> current;       // candidate index per level, -1 = unpaired (the '*' branch)
  std::vector<int> best;
  std::vector<int> paired;        // candidate index per pairing, in tree order
  std::vector<double> L;          // lower Cholesky factor of the joint innovation covariance, row-major
  std::vector<double> y;          // L^-1 nu: the whitened joint innovation
  std::vector<double> W;          // L^-1 B for the pairing under test (2k x 2)
  std::vector<Mat23> HP;          // H_pose_j P per candidate
  // Information form (see Jcbb): per candidate its terms; sums[d] over the first d pairings.
  std::vector<association::CandidateInformation> information;  // written for the listed candidates only
  std::vector<char> has_information;
  std::vector<association::JointInformation> sums;
};

// Depth-first branch and bound over pairings, maximising the number of paired measurements, ties broken by
// the lower joint Mahalanobis distance, then by the lower landmark ids in canonical measurement order.
//   * Levels: only the measurements with an individually compatible candidate, in canonical order.
//   * Individual compatibility is computed once (O(m n)); only gated pairs are branched on.
//   * Joint compatibility of H + (i, j) is tested against chi2(2k) with the joint innovation covariance
//     C = H_x P H_x^T + blockdiag(H_j Sigma_j H_j^T + R), in information form (joint_information.h): running
//     sums of fixed size, so a node costs O(1), one 3x3 solve. Where the problem gives an explicit joint
//     covariance (or some S_j is singular), the Cholesky factor of C grows instead by one 2x2 block row per
//     pairing (O(k^2) forward substitution per node, never a refactorisation), and the joint distance grows
//     by the squared norm of the new whitened innovation block: D2_{k+1} = D2_k + |L22^-1 (nu - W^T y)|^2.
//     D2 never decreases along a branch, which makes the tie-breaking bound exact.
//   * Bound (Neira & Tardós, Fig. 2, tightened): pairings so far + levels left that still have an unused
//     compatible candidate; a branch that cannot beat the best (more pairings, or as many with a lower D2)
//     is pruned.
//   * Budget: after options.max_hypotheses nodes, or options.max_work multiply-adds and candidate scans
//     (the Cholesky form's node costs O(depth^2)), the best hypothesis found so far is returned and
//     stats.budget_exhausted is set. Every returned hypothesis passed its joint test.
class Jcbb {
 public:
  using Scratch = JcbbScratch;
  static constexpr std::string_view kName = "jcbb";
  static constexpr StrategyTraits kTraits{.jointly_compatible = true};

  explicit Jcbb(const AssociationOptions& options);
  void solve(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result) const;

 private:
  double gate_;
  double new_landmark_gate_;
  std::int64_t max_hypotheses_;
  std::int64_t max_work_;
  ChiSquareTable joint_gate_;  // chi2(gate_probability, dof), cached
};

static_assert(AssociationStrategy<Jcbb>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_JCBB_H_
