// The joint compatibility test of a complete answer, computed from scratch (full joint covariance, one
// Cholesky): the reference against which tests, benchmarks and `arbor associate` check every strategy.
#ifndef ARBOR_VARIANTS_ASSOCIATION_JOINT_COMPATIBILITY_H_
#define ARBOR_VARIANTS_ASSOCIATION_JOINT_COMPATIBILITY_H_

#include <vector>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"

namespace arbor::association {

struct JointTest {
  double d2 = 0.0;          // joint Mahalanobis distance nu^T C^-1 nu of the paired measurements
  int dof = 0;              // 2 x pairings
  bool compatible = true;   // d2 <= chi2(probability, dof); an empty hypothesis is compatible
  bool well_formed = true;  // false: unknown id, a landmark paired twice, or C not positive definite
};

// pairing: one entry per measurement, a candidate id or a negative decision (NEW, SPURIOUS, -1).
// C = blocks innovation_covariance(j_a, j_b) over the paired candidates (pose coupling included).
JointTest joint_compatibility(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing,
                              double probability);
// The same with the gate chi2(p, dof) read from a cached table (for callers in a search loop).
JointTest joint_compatibility(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing,
                              const ChiSquareTable& gate);

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_JOINT_COMPATIBILITY_H_
