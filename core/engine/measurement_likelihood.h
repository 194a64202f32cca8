// The measurement likelihood in the FastSLAM weights, the proposal and the landmark updates
// (FastSlamOptions::likelihood): Gaussian, or a 2-D Student-t whose heavier tails keep one outlier from
// deciding a particle's weight.
#ifndef ARBOR_CORE_ENGINE_MEASUREMENT_LIKELIHOOD_H_
#define ARBOR_CORE_ENGINE_MEASUREMENT_LIKELIHOOD_H_

#include <cmath>

#include <Eigen/LU>

#include "core/engine/fastslam_options.h"
#include "core/math/angles.h"
#include "core/math/eigen_types.h"
#include "core/math/ldlt_solve2.h"

namespace arbor {

class MeasurementLikelihood {
 public:
  MeasurementLikelihood(Likelihood kind, double student_dof)
      : kind_(kind), nu_(student_dof),
        student_log_norm_(std::lgamma(0.5 * (nu_ + 2.0)) - std::lgamma(0.5 * nu_) - std::log(nu_ * kPi)) {}

  // The measurement's log-likelihood under innovation covariance S, and the factor by which the update should
  // scale its noise: 1 for the Gaussian, (nu + d^2) / (nu + 2) for the Student-t.
  double operator()(const Vec2& innovation, const Mat2& S, double* noise_scale) const {
    const double d2 = innovation.dot(ldlt_solve2(S, innovation));  // S.ldlt().solve, to the bit
    const double log_det = std::log(S.determinant());
    if (kind_ == Likelihood::kGaussian) {
      *noise_scale = 1.0;
      return -0.5 * d2 - std::log(2.0 * kPi) - 0.5 * log_det;
    }
    *noise_scale = (nu_ + d2) / (nu_ + 2.0);
    return student_log_norm_ - 0.5 * log_det - 0.5 * (nu_ + 2.0) * std::log1p(d2 / nu_);
  }

 private:
  Likelihood kind_;
  double nu_;
  double student_log_norm_;  // log Gamma((nu+2)/2) - log Gamma(nu/2) - log(nu pi), 2-D Student-t
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_MEASUREMENT_LIKELIHOOD_H_
