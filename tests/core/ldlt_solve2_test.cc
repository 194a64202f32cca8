// ldlt_solve2 against Eigen's LDLT<Matrix2d>::solve, to the bit (a NaN's sign aside): the measurement
// likelihood's weights (and so every run) must not move when one replaces the other.
#include "core/math/ldlt_solve2.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace arbor {
namespace {

// The same bits, or both NaN: which operand's NaN an operation propagates, and so its sign, is the
// instruction selection's choice (clang -O1 and gcc -O3 differ on S = [0, .; inf, inf]), not the algorithm's.
bool same_value(double a, double b) { return (std::isnan(a) && std::isnan(b)) || std::memcmp(&a, &b, sizeof a) == 0; }

// Compares one system; returns false (after reporting it) on the first mismatch.
bool agrees(const Mat2& S, const Vec2& b) {
  const Vec2 eigen = S.ldlt().solve(b);
  const Vec2 ours = ldlt_solve2(S, b);
  const bool same = same_value(eigen(0), ours(0)) && same_value(eigen(1), ours(1));
  if (!same)
    ADD_FAILURE() << "S = [" << S(0, 0) << ", " << S(0, 1) << "; " << S(1, 0) << ", " << S(1, 1) << "], b = [" << b(0)
                  << ", " << b(1) << "]: Eigen " << eigen.transpose() << ", ours " << ours.transpose();
  return same;
}

TEST(LdltSolve2, MatchesEigenOnRandomCovariances) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::uniform_real_distribution<double> exponent(-12.0, 12.0);
  for (int i = 0; i < 400000; ++i) {
    // An innovation covariance of any scale and shape (both pivot orders), sometimes not quite symmetric.
    Eigen::Matrix2d A;
    A << unit(rng), unit(rng), unit(rng), unit(rng);
    Mat2 S = std::pow(10.0, exponent(rng)) * (A * A.transpose()) + std::pow(10.0, exponent(rng)) * Mat2::Identity();
    if (i % 3 == 0) S(1, 0) *= 1.0 + 1e-12 * unit(rng);
    const Vec2 b(std::pow(10.0, exponent(rng)) * unit(rng), unit(rng));
    if (!agrees(S, b)) return;
  }
}

TEST(LdltSolve2, MatchesEigenOnDegenerateAndNonFiniteSystems) {
  const double inf = std::numeric_limits<double>::infinity();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double tiny = std::numeric_limits<double>::min();
  const double denormal = std::numeric_limits<double>::denorm_min();
  const std::vector<double> values{0.0, -0.0, 1.0, -1.0, 2.5, -3.0, 1e-300, tiny, denormal, 1e300, inf, -inf, nan};
  int compared = 0;
  for (double a : values)
    for (double c : values)
      for (double d : values)
        for (double e : {0.0, 1.0, -2.0, nan}) {
          Mat2 S;
          S << a, 7.0, c, d;  // the upper triangle is never read
          if (!agrees(S, Vec2(e, 0.5))) return;
          ++compared;
        }
  EXPECT_EQ(compared, 13 * 13 * 13 * 4);
}

}  // namespace
}  // namespace arbor
