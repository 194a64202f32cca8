// The registry: the one place that lists the variants the CLI can choose. Adding a map back end or an
// association strategy is one new header (or .h/.cc pair) plus one line in a list below; tests and
// benchmarks iterate the same lists.
#ifndef ARBOR_VARIANTS_REGISTRY_H_
#define ARBOR_VARIANTS_REGISTRY_H_

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "core/engine/filter.h"
#include "variants/association/strategy_list.h"
#include "variants/maps/hamt_map.h"
#include "variants/maps/persistent_tree_map.h"
#include "variants/maps/vector_map.h"
#include "core/type_list.h"

namespace arbor {

using MapBackends = TypeList<VectorMap, PersistentTreeMap, HamtMap<>>;
// The association strategies are listed once, in variants/association/strategy_list.h; the engine is built
// for those whose traits say in_filter.

// Builds the engine for the named variants and options.version's filter; throws InputError (field "map" or
// "assoc") listing the valid names. A filter without map back ends (variants/filter_list.h) ignores map.
std::unique_ptr<Filter> make_filter(std::string_view map, std::string_view assoc, const Scenario& scenario,
                                    const FastSlamOptions& options);

// Inline, so that reading a sweep spec (which checks names against these) does not link the engine.
template <class... T>
std::vector<std::string> type_names(TypeList<T...>) {
  return {std::string(T::kName)...};
}
inline std::vector<std::string> map_backend_names() { return type_names(MapBackends{}); }
inline std::vector<std::string> association_names() { return filter_strategy_names(); }  // usable in the filter

// The engine instantiations of one map back end with every strategy. Each back end's instantiations live
// in their own translation unit (variants/engine/filters_<name>.cc, one ARBOR_INSTANTIATE_FILTERS line) so
// the cross product compiles in parallel, as Ceres spreads its Schur specialisations over files.
// make.template operator()<S>() for the strategy S usable in the filter whose name is assoc; null if none. The
// engines' instantiation files (variants/engine/) build theirs through it.
template <class Make, class... Strategies>
std::unique_ptr<Filter> make_for_strategy(TypeList<Strategies...>, std::string_view assoc, const Make& make) {
  std::unique_ptr<Filter> filter;
  const auto visit = [&]<class S>() {
    if constexpr (S::kTraits.in_filter)
      if (!filter && assoc == S::kName) filter = make.template operator()<S>();
  };
  (visit.template operator()<Strategies>(), ...);
  return filter;
}

// EKF-SLAM with every strategy usable in the filter (variants/engine/filters_ekf.cc).
std::unique_ptr<Filter> make_ekf_filter(std::string_view assoc, const Scenario& scenario, const FastSlamOptions& options);

template <LandmarkMap Map>
std::unique_ptr<Filter> make_filter_for_map(std::string_view assoc, const Scenario& scenario,
                                            const FastSlamOptions& options);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_REGISTRY_H_
