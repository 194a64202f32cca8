// Joint chi-square test of a whole pairing with an explicit joint innovation covariance.
#include "variants/association/joint_compatibility.h"

#include <algorithm>
#include <unordered_map>

#include <Eigen/Cholesky>

#include "core/math/chi_square.h"
#include "core/models/range_bearing_model.h"

namespace arbor::association {

namespace {

// d2 and dof of the pairing, or well_formed = compatible = false; compatible is left true otherwise (the
// caller gates d2).
JointTest joint_distance(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing) {
  JointTest test;
  std::unordered_map<LandmarkId, int> index;
  for (int j = 0; j < static_cast<int>(problem.candidates.size()); ++j) index[problem.candidates[j].id] = j;
  std::vector<int> meas, cand;
  for (int i = 0; i < static_cast<int>(pairing.size()); ++i) {
    if (pairing[i] < 0) continue;
    const auto it = index.find(pairing[i]);
    if (it == index.end() || std::find(cand.begin(), cand.end(), it->second) != cand.end()) {
      test.well_formed = test.compatible = false;
      return test;
    }
    meas.push_back(i);
    cand.push_back(it->second);
  }
  const int k = static_cast<int>(cand.size());
  test.dof = 2 * k;
  if (k == 0) return test;
  Eigen::MatrixXd C(2 * k, 2 * k);
  Eigen::VectorXd nu(2 * k);
  for (int a = 0; a < k; ++a) {
    nu.segment<2>(2 * a) = range_bearing_innovation(problem.measurements[meas[a]].z, problem.candidates[cand[a]].z_hat);
    for (int b = 0; b < k; ++b) C.block<2, 2>(2 * a, 2 * b) = problem.innovation_covariance(cand[a], cand[b]);
  }
  C = 0.5 * (C + C.transpose()).eval();
  Eigen::LLT<Eigen::MatrixXd> llt(C);
  if (llt.info() != Eigen::Success) {
    test.well_formed = test.compatible = false;
    return test;
  }
  test.d2 = nu.dot(llt.solve(nu));
  return test;
}

}  // namespace

JointTest joint_compatibility(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing,
                              double probability) {
  JointTest test = joint_distance(problem, pairing);
  if (test.well_formed && test.dof > 0) test.compatible = test.d2 <= chi_square_quantile(probability, test.dof);
  return test;
}

JointTest joint_compatibility(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing,
                              const ChiSquareTable& gate) {
  JointTest test = joint_distance(problem, pairing);
  if (test.well_formed && test.dof > 0) test.compatible = test.d2 <= gate(test.dof);
  return test;
}

}  // namespace arbor::association
