// Log-space weight normalisation and systematic (low-variance) resampling (Probabilistic Robotics, Table 4.4).
// Both run serially in particle order, so the sums come out identical for any thread count; the copies of the
// chosen particles run in parallel.
#ifndef ARBOR_CORE_ENGINE_RESAMPLING_H_
#define ARBOR_CORE_ENGINE_RESAMPLING_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/check.h"
#include "core/engine/numerical_breakdown.h"
#include "core/math/eigen_types.h"

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

// normalize_log_weights over the particles' log weights, which become log w: returns N_eff. step names the
// step in the error a NaN weight raises.
template <class Particle>
double normalize_particle_weights(std::vector<Particle>* particles, std::vector<double>* weights, std::int64_t step) {
  std::vector<double> log_weights(particles->size());
  for (std::size_t i = 0; i < particles->size(); ++i) {
    log_weights[i] = (*particles)[i].log_weight;
    // Not an abort: huge motion noise or controls within the scenario limits can swamp the weights.
    if (std::isnan(log_weights[i]))
      throw NumericalBreakdown(fmt::format("NaN weight for particle {} at step {}", i, step));
  }
  const double n_eff = normalize_log_weights(log_weights, weights);
  for (std::size_t i = 0; i < particles->size(); ++i) (*particles)[i].log_weight = std::log((*weights)[i]);
  return n_eff;
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

// Regularised resampling (Musso, Oudjane & Le Gland 2001): the covariance added to every pose after a
// resampling, (roughen h_opt)^2 times the set's, with h_opt = (4 / (M (d + 2)))^(1 / (d + 4)) for d = 3.
inline Mat3 roughening_kernel(double roughen, int particles, const Mat3& set_covariance) {
  constexpr double d = 3.0;  // the pose's dimension
  const double h = roughen * std::pow(4.0 / (particles * (d + 2.0)), 1.0 / (d + 4.0));
  return h * h * set_covariance;
}

// Replaces *particles by the children that parents names (systematic_resample's, non-decreasing), in parallel.
// A run's last child takes its parent by move and the others copy it: a particle drawn once costs nothing, and
// a persistent map whose nodes it no longer shares is updated in place rather than path-copied. The parents
// not drawn are released in parallel too: for the naive back end freeing is as costly as copying.
template <class Particle>
void take_children(const std::vector<int>& parents, std::vector<Particle>* particles, tbb::task_arena& arena) {
  const int m = static_cast<int>(parents.size());
  std::vector<int> first_child(m, -1);  // per particle: its first child (parents is non-decreasing), or -1
  for (int i = m - 1; i >= 0; --i) first_child[parents[i]] = i;
  std::vector<Particle> next(m);
  // One parallel pass over the old particles, each copied into its children or, not drawn, released: two
  // passes cost more in scheduling than the work (results/engine/b0ab821_vm_gcc-12.2.0/).
  arena.execute([&] {
    tbb::parallel_for(0, m, [&](int j) {
      Particle& parent = (*particles)[j];
      if (first_child[j] < 0) {
        parent = Particle{};
        return;
      }
      int last = first_child[j];
      while (last + 1 < m && parents[last + 1] == j) ++last;
      for (int i = first_child[j]; i < last; ++i) next[i] = parent;
      next[last] = std::move(parent);
    });
  });
  particles->swap(next);
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RESAMPLING_H_
