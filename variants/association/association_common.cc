// Individual gating and the canonical measurement order shared by the association strategies.
#include "variants/association/association_common.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/models/range_bearing_model.h"

namespace arbor::association {

void gate_individually(const AssociationProblem& problem, double gate, double new_landmark_gate,
                       IndividualGating* gating, AssociationStats* stats) {
  const int m = static_cast<int>(problem.measurements.size());
  const int n = static_cast<int>(problem.candidates.size());
  gating->pairs.clear();
  gating->first.assign(m + 1, 0);
  gating->near_any.assign(m, 0);
  // C_jj^-1 once per candidate; a degenerate covariance makes the candidate unmatchable rather than wrong.
  std::vector<Mat2>& inverse = gating->inverse;
  std::vector<char>& valid = gating->valid;
  std::vector<double>& reach2 = gating->reach2;
  inverse.resize(n);
  valid.resize(n);
  reach2.resize(n);
  // The range innovation alone bounds the distance: d^2 = nu^T C^-1 nu >= nu_r^2 / C_rr (minimised over the
  // bearing innovation, the Schur complement). A pair whose range puts it past both gates is passed over before
  // its bearing is wrapped and its form evaluated; the margin of 1e-6 outweighs the rounding of C^-1 for
  // condition numbers up to about 1e9, so the pairs kept and their distances are those of the full test.
  const double outer_gate = std::max(gate, new_landmark_gate);
  for (int j = 0; j < n; ++j) {
    Mat2 c = problem.innovation_covariance(j, j);
    c = 0.5 * (c + c.transpose());
    valid[j] = invert_spd2(c, &inverse[j]);
    reach2[j] = outer_gate * c(0, 0) * (1.0 + 1e-6);
  }
  for (int i = 0; i < m; ++i) {
    gating->first[i] = static_cast<int>(gating->pairs.size());
    const Vec2& z = problem.measurements[i].z;
    for (int j = 0; j < n; ++j) {
      if (!valid[j]) continue;
      const double range_innovation = z.x() - problem.candidates[j].z_hat.x();
      if (range_innovation * range_innovation > reach2[j]) continue;
      const Vec2 nu = range_bearing_innovation(z, problem.candidates[j].z_hat);
      const double d2 = nu.dot(inverse[j] * nu);
      if (d2 <= new_landmark_gate) gating->near_any[i] = 1;
      if (d2 <= gate) gating->pairs.push_back({d2, i, j});
    }
  }
  gating->first[m] = static_cast<int>(gating->pairs.size());
  stats->tests += static_cast<std::int64_t>(m) * n;
}

void pair_greedily(const AssociationProblem& problem, const std::vector<int>& rank, std::vector<GatedPair>* pairs,
                   std::vector<char>* taken, std::vector<LandmarkId>* pairing) {
  const auto id_of = [&](const GatedPair& p) { return problem.candidates[p.candidate].id; };
  std::sort(pairs->begin(), pairs->end(), [&](const GatedPair& a, const GatedPair& b) {
    if (a.d2 != b.d2) return a.d2 < b.d2;
    if (id_of(a) != id_of(b)) return id_of(a) < id_of(b);
    return rank[a.measurement] < rank[b.measurement];
  });
  for (const GatedPair& p : *pairs) {
    if ((*pairing)[p.measurement] != kUnassigned || (*taken)[p.candidate]) continue;
    (*pairing)[p.measurement] = id_of(p);
    (*taken)[p.candidate] = 1;
  }
}

void canonical_measurement_order(const AssociationProblem& problem, std::vector<int>* order) {
  const auto& ms = problem.measurements;
  order->resize(ms.size());
  std::iota(order->begin(), order->end(), 0);
  std::sort(order->begin(), order->end(), [&](int a, int b) {
    const auto& x = ms[a];
    const auto& y = ms[b];
    if (x.z.x() != y.z.x()) return x.z.x() < y.z.x();
    if (x.z.y() != y.z.y()) return x.z.y() < y.z.y();
    const bool xs = std::isnan(x.signature), ys = std::isnan(y.signature);
    if (xs != ys) return xs;
    if (!xs && x.signature != y.signature) return x.signature < y.signature;
    return a < b;
  });
}

}  // namespace arbor::association
