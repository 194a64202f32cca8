// Runs a standalone association strategy chosen by name (for `arbor associate`, `arbor relocalize` and the
// benchmarks). The engine's list is AssociationStrategies in variants/registry.h; this one adds the
// unrestricted interpretation tree, which is a baseline for the locality tree, not a per-particle strategy.
#ifndef ARBOR_VARIANTS_ASSOCIATION_STRATEGY_DISPATCH_H_
#define ARBOR_VARIANTS_ASSOCIATION_STRATEGY_DISPATCH_H_

#include <string>
#include <string_view>
#include <vector>

#include "variants/association/interpretation_tree.h"
#include "variants/association/jcbb.h"
#include "variants/association/locality_tree.h"
#include "variants/association/nearest_neighbor.h"

namespace arbor {

template <class... S>
struct StrategyList {};
using StandaloneStrategies =
    StrategyList<NearestNeighbor, NearestNeighborNoExclusion, Jcbb, LocalityTree, InterpretationTree>;

// Calls f(strategy_type_tag) as f.template operator()<S>() for the strategy named `name`; false if unknown.
template <class F, class... S>
bool visit_strategy(StrategyList<S...>, std::string_view name, F&& f) {
  bool found = false;
  ((!found && name == S::kName ? (void)(found = true, f.template operator()<S>()) : (void)0), ...);
  return found;
}

template <class... S>
std::vector<std::string> strategy_names(StrategyList<S...>) {
  return {std::string(S::kName)...};
}

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_STRATEGY_DISPATCH_H_
