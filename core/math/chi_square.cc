// Chi-square CDF and quantiles (see chi_square.h).
#include "core/math/chi_square.h"

#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>
#include <vector>

#include "core/check.h"

namespace arbor {
namespace {

// Regularised lower incomplete gamma P(a, x).
double gamma_p(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {  // series: P = e^-x x^a / Gamma(a+1) * sum x^n / ((a+1)...(a+n))
    double term = 1.0 / a, sum = term;
    for (int n = 1; n < 1000; ++n) {
      term *= x / (a + n);
      sum += term;
      if (std::abs(term) < std::abs(sum) * 1e-16) break;
    }
    return sum * std::exp(log_prefactor);
  }
  // Continued fraction for Q = 1 - P (modified Lentz).
  const double tiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / tiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 1000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return 1.0 - std::exp(log_prefactor) * h;
}

}  // namespace

double chi_square_cdf(double x, int dof) { return gamma_p(0.5 * dof, 0.5 * x); }

double chi_square_quantile(double p, int dof) {
  ARBOR_CHECK(p > 0.0 && p < 1.0 && dof >= 1, "p={} dof={}", p, dof);
  double lo = 0.0, hi = dof + 10.0 * std::sqrt(2.0 * dof) + 50.0;
  while (chi_square_cdf(hi, dof) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (chi_square_cdf(mid, dof) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

ChiSquareTable::ChiSquareTable(double p, int max_dof) : p_(p), max_dof_(max_dof) {
  static std::mutex mutex;
  static std::map<std::pair<double, int>, std::unique_ptr<std::vector<double>>> cache;
  std::lock_guard lock(mutex);
  auto& entry = cache[{p, max_dof}];
  if (!entry) {
    entry = std::make_unique<std::vector<double>>(max_dof + 1, 0.0);
    for (int dof = 1; dof <= max_dof; ++dof) (*entry)[dof] = chi_square_quantile(p, dof);
  }
  table_ = entry->data();
}

double ChiSquareTable::operator()(int dof) const {
  if (dof <= max_dof_) return table_[dof];
  return chi_square_quantile(p_, dof);
}

}  // namespace arbor
