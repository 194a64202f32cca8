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

#include <cmath>
#include <utility>

#include "core/association/association_problem.h"
#include "core/math/eigen_types.h"
#include "variants/association/association_common.h"

namespace arbor::association {

// A^-1 y for a 3x3 A by LU with partial pivoting: Eigen 3.4's PartialPivLU<Mat3>::solve, operation for
// operation and in its order (PartialPivLU.h's unblocked_lu, then SolveTriangular.h's unrolled unit-lower and
// upper solves), so the result is the same to the bit (tests/association/jcbb_test.cc compares the two on
// random and pivoting systems). What it leaves out is bookkeeping the distance never reads (the permutation
// matrix, the L1 norm kept for rcond()): on Victoria Park the general code took a sixth of JCBB's time.
inline Vec3 solve3_partial_pivot(Mat3 a, Vec3 y) {
  for (int k = 0; k < 2; ++k) {
    int pivot = k;
    double biggest = std::abs(a(k, k));
    for (int i = k + 1; i < 3; ++i)
      if (std::abs(a(i, k)) > biggest) {
        biggest = std::abs(a(i, k));
        pivot = i;
      }
    if (biggest != 0.0) {
      if (pivot != k) {
        a.row(k).swap(a.row(pivot));
        std::swap(y(k), y(pivot));
      }
      for (int i = k + 1; i < 3; ++i) a(i, k) /= a(k, k);
    }
    for (int j = k + 1; j < 3; ++j)
      for (int i = k + 1; i < 3; ++i) a(i, j) -= a(i, k) * a(k, j);
  }
  y(1) -= a(1, 0) * y(0);
  y(2) -= a(2, 0) * y(0) + a(2, 1) * y(1);
  y(2) /= a(2, 2);
  y(1) -= a(1, 2) * y(2);
  y(1) /= a(1, 1);
  y(0) -= a(0, 1) * y(1) + a(0, 2) * y(2);
  y(0) /= a(0, 0);
  return y;
}

// One candidate's terms: S^-1, H^T S^-1 and H^T S^-1 H (H = d h / d pose).
struct CandidateInformation {
  Mat2 S_inv;
  Mat32 HtSinv;
  Mat3 HtSinvH;
};

// Whether candidate_information succeeds: the candidate's individual covariance S is positive definite.
inline bool candidate_information_exists(const AssociationCandidate& c) { return is_spd2(0.5 * (c.S + c.S.transpose())); }

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
    const Vec3 x = solve3_partial_pivot(Mat3::Identity() + P * J, P * b);
    return s - b.dot(x);
  }
};

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_JOINT_INFORMATION_H_
