// The one list of association strategies. Each strategy's StrategyTraits say where it is offered: the
// engine instantiates those usable in the filter (variants/registry.h), `arbor associate`, `arbor
// relocalize` and the benchmarks pick from the standalone ones, and the conformance suite checks every
// strategy against what its traits promise. A new strategy is one header plus one entry here.
#ifndef ARBOR_VARIANTS_ASSOCIATION_STRATEGY_LIST_H_
#define ARBOR_VARIANTS_ASSOCIATION_STRATEGY_LIST_H_

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "variants/association/jcbb.h"
#include "variants/association/known_association.h"
#include "variants/association/nearest_neighbor.h"
#include "variants/association/tree_strategy.h"
#include "core/type_list.h"

namespace arbor {

using AssociationStrategies =
    TypeList<KnownAssociation, NearestNeighbor, NearestNeighborNoExclusion, Jcbb, LocalityTree, InterpretationTree>;

// The names of the strategies whose traits satisfy keep(traits), in list order.
template <class Keep, class... S>
std::vector<std::string> strategy_names_where(TypeList<S...>, Keep keep) {
  std::vector<std::string> names;
  ((keep(S::kTraits) ? (void)names.emplace_back(S::kName) : (void)0), ...);
  return names;
}
inline std::vector<std::string> standalone_strategy_names() {
  return strategy_names_where(AssociationStrategies{}, [](const StrategyTraits& t) { return t.standalone; });
}
inline std::vector<std::string> filter_strategy_names() {
  return strategy_names_where(AssociationStrategies{}, [](const StrategyTraits& t) { return t.in_filter; });
}

// Whether the strategy named `name` pairs by the scenario's true ids (StrategyTraits::uses_ground_truth).
inline bool strategy_uses_ground_truth(std::string_view name) {
  const std::vector<std::string> oracles =
      strategy_names_where(AssociationStrategies{}, [](const StrategyTraits& t) { return t.uses_ground_truth; });
  return std::find(oracles.begin(), oracles.end(), name) != oracles.end();
}

namespace internal {
template <class F, class... S>
bool visit_standalone(TypeList<S...>, std::string_view name, F& f) {
  bool found = false;
  const auto visit = [&]<class A>() {
    if constexpr (A::kTraits.standalone) {
      if (!found && name == A::kName) {
        found = true;
        f.template operator()<A>();
      }
    }
  };
  (visit.template operator()<S>(), ...);
  return found;
}
}  // namespace internal

// Calls f.template operator()<S>() for the standalone strategy named `name`; false if there is none.
template <class F>
bool visit_strategy(std::string_view name, F&& f) {
  return internal::visit_standalone(AssociationStrategies{}, name, f);
}

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_STRATEGY_LIST_H_
