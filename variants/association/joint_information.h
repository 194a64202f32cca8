// The joint compatibility distance in information form, for problems whose joint innovation covariance has
// the structure C = H P H^T + blockdiag(S_i) (no explicit joint covariance). By the Woodbury identity
//   nu^T C^-1 nu = s - b^T (P^-1 + J)^-1 b = s - b^T (I + P J)^-1 P b,
// with J = sum H_i^T S_i^-1 H_i, b = sum H_i^T S_i^-1 nu_i and s = sum nu_i^T S_i^-1 nu_i over the pairings:
// three sums of fixed size, so a pairing is added in O(1) and the distance is one 3x3 solve, where the
// dense form costs a (2k)^3 Cholesky factorisation. P need not be invertible: I + P J is, for P and J
// positive semi-definite. The dense form (joint_compatibility.h) remains the reference the tests check
// every strategy against.
#ifndef ARBOR_VARIANTS_ASSOCIATION_JOINT_INFORMATION_H_
#define ARBOR_VARIANTS_ASSOCIATION_JOINT_INFORMATION_H_

#include <Eigen/LU>

#include "core/association/association_problem.h"
#include "core/math/eigen_types.h"
#include "variants/association/association_common.h"

namespace arbor::association {

// One candidate's terms: S^-1, H^T S^-1 and H^T S^-1 H (H = d h / d pose).
struct CandidateInformation {
  Mat2 S_inv;
  Mat32 HtSinv;
  Mat3 HtSinvH;
};

// False when the candidate's individual covariance S is not positive definite (use the dense form).
inline bool candidate_information(const AssociationCandidate& c, CandidateInformation* out) {
  if (!invert_spd2(0.5 * (c.S + c.S.transpose()), &out->S_inv)) return false;
  out->HtSinv = c.H_pose.transpose() * out->S_inv;
  out->HtSinvH = out->HtSinv * c.H_pose;
  return true;
}

struct JointInformation {
  Mat3 J = Mat3::Zero();
  Vec3 b = Vec3::Zero();
  double s = 0.0;

  // The sums with one more pairing (innovation nu against the candidate with terms c).
  JointInformation plus(const CandidateInformation& c, const Vec2& nu) const {
    return {J + c.HtSinvH, b + c.HtSinv * nu, s + nu.dot(c.S_inv * nu)};
  }
  // The joint Mahalanobis distance of the pairings summed so far, with pose covariance P.
  double distance(const Mat3& P) const {
    const Vec3 x = (Mat3::Identity() + P * J).partialPivLu().solve(P * b);
    return s - b.dot(x);
  }
};

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_JOINT_INFORMATION_H_
