// S^-1 b for a 2x2 S by Eigen 3.4's LDLT<Matrix2d> (lower triangle, diagonal pivoting), operation for
// operation and in its order: LDLT.h's ldlt_inplace<Lower>::unblocked, then _solve_impl_transposed with its
// pseudo-inverse of D (entries at or below the smallest normal double count as zero). The result is the same
// to the bit, a NaN's sign aside (tests/core/ldlt_solve2_test.cc compares the two on random, degenerate and
// non-finite systems).
// What it leaves out is what a solve never reads: the L1 norm that LDLT::compute keeps for rcond(), the sign
// and the info flags. The measurement likelihood solves one such system per pairing and particle (Eigen's
// general code for it was 3 % of a Victoria Park run); loop closing's and known association's gates use it too,
// so every 2x2 Mahalanobis distance in the engine is computed one way.
#ifndef ARBOR_CORE_MATH_LDLT_SOLVE2_H_
#define ARBOR_CORE_MATH_LDLT_SOLVE2_H_

#include <cmath>
#include <limits>
#include <utility>

#include "core/math/eigen_types.h"

namespace arbor {

inline Vec2 ldlt_solve2(const Mat2& S, const Vec2& b) {
  // Factor: the larger diagonal entry by magnitude (the first on a tie or a NaN) becomes the first pivot.
  double d0 = S(0, 0), d1 = S(1, 1), l = S(1, 0);
  const bool swapped = std::abs(d1) > std::abs(d0);
  if (swapped) std::swap(d0, d1);
  // A zero or NaN first pivot (then nothing was swapped): Eigen stops with l unscaled and d1 as it was.
  if (std::abs(d0) > 0.0) {
    l /= d0;
    d1 -= l * (d0 * l);
  }
  // Solve: P b, L^-1, the pseudo-inverse of D, L^-T, P^T.
  constexpr double kTiny = std::numeric_limits<double>::min();
  Vec2 y = b;
  if (swapped) std::swap(y(0), y(1));
  y(1) -= l * y(0);
  y(0) = std::abs(d0) > kTiny ? y(0) / d0 : 0.0;
  y(1) = std::abs(d1) > kTiny ? y(1) / d1 : 0.0;
  y(0) -= l * y(1);
  if (swapped) std::swap(y(0), y(1));
  return y;
}

}  // namespace arbor

#endif  // ARBOR_CORE_MATH_LDLT_SOLVE2_H_
