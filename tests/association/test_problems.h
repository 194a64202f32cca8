// Problem builders shared by the association tests.
#ifndef ARBOR_TESTS_ASSOCIATION_TEST_PROBLEMS_H_
#define ARBOR_TESTS_ASSOCIATION_TEST_PROBLEMS_H_

#include <vector>

#include "core/association/association_problem.h"
#include "core/models/range_bearing_model.h"

namespace arbor::testing {

// A candidate at world position m seen from the prior pose x with landmark covariance sigma and noise R.
inline AssociationCandidate make_candidate(LandmarkId id, const Pose2& x, const Vec2& m, const Mat2& sigma,
                                           const Mat2& R) {
  AssociationCandidate c;
  c.id = id;
  Mat2 H;
  c.z_hat = range_bearing_predict(x, m, &H, &c.H_pose);
  c.S = H * sigma * H.transpose() + R;
  c.position = m;
  c.position_cov = sigma;
  return c;
}

inline AssociationMeasurement make_measurement(double r, double phi) {
  AssociationMeasurement z;
  z.z = Vec2(r, phi);
  return z;
}

// One solve of p by strategy S with options o, from fresh scratch.
template <class S>
AssociationResult solve_with(const AssociationProblem& p, AssociationOptions o = {}) {
  const S strategy(o);
  typename S::Scratch scratch;
  AssociationResult r;
  strategy.solve(p, scratch, r);
  return r;
}

}  // namespace arbor::testing

#endif  // ARBOR_TESTS_ASSOCIATION_TEST_PROBLEMS_H_
