// Gated nearest neighbour with and without greedy mutual exclusion.
#include "variants/association/nearest_neighbor.h"

#include "core/math/chi_square.h"

namespace arbor {

void solve_nearest_neighbor(const AssociationProblem& problem, double gate, double new_landmark_gate,
                            bool exclusive, NearestNeighborScratch& scratch, AssociationResult& result) {
  using association::GatedPair;
  const int m = static_cast<int>(problem.measurements.size());
  result.stats = {};
  result.pairing.assign(m, association::kUnassigned);
  association::gate_individually(problem, gate, new_landmark_gate, &scratch.gating, &result.stats);
  auto& pairs = scratch.gating.pairs;
  const auto id_of = [&](const GatedPair& p) { return problem.candidates[p.candidate].id; };
  if (!exclusive) {
    for (int i = 0; i < m; ++i) {
      const GatedPair* best = nullptr;
      for (int k = scratch.gating.first[i]; k < scratch.gating.first[i + 1]; ++k) {
        const GatedPair& p = pairs[k];
        if (!best || p.d2 < best->d2 || (p.d2 == best->d2 && id_of(p) < id_of(*best))) best = &p;
      }
      if (best) result.pairing[i] = id_of(*best);
    }
  } else {
    association::canonical_measurement_order(problem, &scratch.order);
    scratch.rank.resize(m);
    for (int k = 0; k < m; ++k) scratch.rank[scratch.order[k]] = k;
    scratch.taken.assign(problem.candidates.size(), 0);
    association::pair_greedily(problem, scratch.rank, &pairs, &scratch.taken, &result.pairing);
  }
  result.stats.hypotheses = 1;
  association::finish_unpaired(scratch.gating.near_any, &result.pairing);
}

}  // namespace arbor
