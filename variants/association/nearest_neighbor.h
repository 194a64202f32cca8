// Nearest-neighbour association (DESIGN.md §4): each measurement takes its maximum-likelihood candidate inside
// a chi-square gate (2 dof). NearestNeighbor enforces mutual exclusion greedily over all gated pairs;
// NearestNeighborNoExclusion lets several measurements take the same landmark (the textbook gated NN).
#ifndef ARBOR_VARIANTS_ASSOCIATION_NEAREST_NEIGHBOR_H_
#define ARBOR_VARIANTS_ASSOCIATION_NEAREST_NEIGHBOR_H_

#include <string_view>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "variants/association/association_common.h"

namespace arbor {

struct NearestNeighborScratch {
  association::IndividualGating gating;
  std::vector<int> order;  // canonical measurement order
  std::vector<int> rank;   // rank[i]: position of measurement i in that order
  std::vector<char> taken;
};

// Runs NN with or without mutual exclusion; gates are chi-square thresholds (2 dof).
void solve_nearest_neighbor(const AssociationProblem& problem, double gate, double new_landmark_gate,
                            bool exclusive, NearestNeighborScratch& scratch, AssociationResult& result);

// Mutual exclusion resolved greedily: all gated pairs sorted by (Mahalanobis distance, landmark id, the
// measurement's canonical rank) and accepted when neither side is taken yet, so the answer does not depend on
// the order of the input. Greedy, not optimal (that is what JCBB is for).
template <bool kExclusive>
class NearestNeighborStrategy {
 public:
  using Scratch = NearestNeighborScratch;
  static constexpr std::string_view kName = kExclusive ? "nn" : "nn-independent";
  static constexpr StrategyTraits kTraits{.mutually_exclusive = kExclusive};

  explicit NearestNeighborStrategy(const AssociationOptions& options)
      : gate_(chi_square_quantile(options.gate_probability, 2)),
        new_landmark_gate_(chi_square_quantile(options.new_landmark_probability, 2)) {}
  void solve(const AssociationProblem& problem, Scratch& scratch, AssociationResult& result) const {
    solve_nearest_neighbor(problem, gate_, new_landmark_gate_, kExclusive, scratch, result);
  }

 private:
  double gate_;
  double new_landmark_gate_;
};

using NearestNeighbor = NearestNeighborStrategy<true>;
// Each measurement takes its most likely landmark, even one another measurement also took.
using NearestNeighborNoExclusion = NearestNeighborStrategy<false>;

static_assert(AssociationStrategy<NearestNeighbor>);
static_assert(AssociationStrategy<NearestNeighborNoExclusion>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_NEAREST_NEIGHBOR_H_
