// Chi-square quantiles for the association gates: chi2inv(p, dof) by inverting the regularised lower
// incomplete gamma function P(dof/2, x/2) (series and continued fraction, Press et al., Numerical Recipes §6.2).
#ifndef ARBOR_CORE_MATH_CHI_SQUARE_H_
#define ARBOR_CORE_MATH_CHI_SQUARE_H_

namespace arbor {

// P(X <= x) for X ~ chi-square with dof degrees of freedom.
double chi_square_cdf(double x, int dof);

// The x with chi_square_cdf(x, dof) = p, for 0 < p < 1 and dof >= 1; accurate to ~1e-12 relative.
double chi_square_quantile(double p, int dof);

// chi_square_quantile(p, dof) for dof = 1..max_dof, cached per p: gates are evaluated in inner loops.
class ChiSquareTable {
 public:
  ChiSquareTable() = default;
  ChiSquareTable(double p, int max_dof);
  double operator()(int dof) const;
  double probability() const { return p_; }

 private:
  double p_ = 0.0;
  int max_dof_ = 0;
  double* table_ = nullptr;  // owned by a process-wide cache keyed by (p, max_dof); never freed
};

}  // namespace arbor

#endif  // ARBOR_CORE_MATH_CHI_SQUARE_H_
