// Log-space weight normalisation and systematic (low-variance) resampling (Probabilistic Robotics, Table 4.4).
// Both run serially in particle order, so the sums come out identical for any thread count.
#ifndef ARBOR_CORE_ENGINE_RESAMPLING_H_
#define ARBOR_CORE_ENGINE_RESAMPLING_H_

#include <algorithm>
#include <cmath>
#include <vector>

namespace arbor {

// Turns log weights into normalised linear weights with log-sum-exp; returns N_eff = 1 / sum(w^2).
inline double normalize_log_weights(const std::vector<double>& log_weights, std::vector<double>* weights) {
  const double max_log = *std::max_element(log_weights.begin(), log_weights.end());
  weights->resize(log_weights.size());
  double sum = 0.0;
  for (std::size_t i = 0; i < log_weights.size(); ++i) sum += ((*weights)[i] = std::exp(log_weights[i] - max_log));
  double sum_sq = 0.0;
  for (double& w : *weights) {
    w /= sum;
    sum_sq += w * w;
  }
  return 1.0 / sum_sq;
}

// Systematic resampling: one uniform u in (0, 1) places M equally spaced pointers on the cumulative weights.
// Returns, for each new particle, the index of its parent (non-decreasing).
inline std::vector<int> systematic_resample(const std::vector<double>& weights, double u) {
  const int m = static_cast<int>(weights.size());
  std::vector<int> parents(m);
  double cumulative = weights[0];
  int i = 0;
  for (int j = 0; j < m; ++j) {
    const double pointer = (u + j) / m;
    while (pointer > cumulative && i < m - 1) cumulative += weights[++i];
    parents[j] = i;
  }
  return parents;
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RESAMPLING_H_
