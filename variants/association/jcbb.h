// Joint Compatibility Branch and Bound (Neira & Tardós 2001, IEEE T-RA 17(6)): the hypothesis with the most
// pairings whose joint innovation passes a chi-square test, the pose covariance's correlations included.
#ifndef ARBOR_VARIANTS_ASSOCIATION_JCBB_H_
#define ARBOR_VARIANTS_ASSOCIATION_JCBB_H_

#include <string_view>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "variants/association/association_common.h"

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
  // Information form (see Jcbb): per candidate S^-1, H^T S^-1 and H^T S^-1 H; per depth the running sums.
  std::vector<Mat2> Sinv;
  std::vector<Mat32> HtSinv;
  std::vector<Mat3> HtSinvH;
  std::vector<Mat3> info;         // info[d] = sum of H^T S^-1 H over the first d pairings
  std::vector<Vec3> info_vec;     // info_vec[d] = sum of H^T S^-1 nu
  std::vector<double> info_sum;   // info_sum[d] = sum of nu^T S^-1 nu
};

// Depth-first branch and bound over pairings, maximising the number of paired measurements, ties broken by
// the lower joint Mahalanobis distance, then by the lower landmark ids in canonical measurement order.
//   * Levels: only the measurements with an individually compatible candidate, in canonical order.
//   * Individual compatibility is computed once (O(m n)); only gated pairs are branched on.
//   * Joint compatibility of H + (i, j) is tested against chi2(2k) with the joint innovation covariance
//     C = H_x P H_x^T + blockdiag(H_j Sigma_j H_j^T + R). Its Cholesky factor grows by one 2x2 block row per
//     pairing (O(k^2) forward substitution per node, never a refactorisation), and the joint distance grows by
//     the squared norm of the new whitened innovation block:  D2_{k+1} = D2_k + |L22^-1 (nu - W^T y)|^2.
//     D2 never decreases along a branch, which makes the tie-breaking bound exact.
//   * When the joint covariance has that structure (no explicit joint covariance in the problem), the test
//     runs in the information form instead: by the Woodbury identity, with J = sum H_i^T S_i^-1 H_i,
//     b = sum H_i^T S_i^-1 nu_i and s = sum nu_i^T S_i^-1 nu_i over the pairings,
//       D2 = s - b^T (P^-1 + J)^-1 b = s - b^T (I + P J)^-1 P b,
//     three running sums of fixed size, so a node costs O(1) (a 3x3 solve) instead of O(k^2), and P need not
//     be invertible (I + P J is, for P and J positive semi-definite).
//   * Bound (Neira & Tardós, Fig. 2, tightened): pairings so far + levels left that still have an unused
//     compatible candidate; a branch that cannot beat the best (more pairings, or as many with a lower D2)
//     is pruned.
//   * Budget: after options.max_hypotheses nodes the best hypothesis found so far is returned and
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
  ChiSquareTable joint_gate_;  // chi2(gate_probability, dof), cached
};

static_assert(AssociationStrategy<Jcbb>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_JCBB_H_
