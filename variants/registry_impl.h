// Definition of make_filter_for_map; included only by the per-back-end instantiation files.
#ifndef ARBOR_VARIANTS_REGISTRY_IMPL_H_
#define ARBOR_VARIANTS_REGISTRY_IMPL_H_

#include "variants/association/locality_relocalizer.h"
#include "variants/registry.h"

namespace arbor {
namespace internal {

template <LandmarkMap Map, class... Strategies>
std::unique_ptr<Filter> make_with_strategy(TypeList<Strategies...>, std::string_view assoc, const Scenario& scenario,
                                           const FastSlamOptions& options) {
  std::unique_ptr<Filter> filter;
  const auto make = [&]<class S>() {
    if constexpr (S::kTraits.in_filter)
      if (!filter && assoc == S::kName)
        filter = std::make_unique<FilterImpl<Map, S>>(
            scenario, options, options.relocalize ? make_locality_relocalizer(options.association) : Relocalizer{});
  };
  (make.template operator()<Strategies>(), ...);
  return filter;
}

}  // namespace internal

template <LandmarkMap Map>
std::unique_ptr<Filter> make_filter_for_map(std::string_view assoc, const Scenario& scenario,
                                            const FastSlamOptions& options) {
  return internal::make_with_strategy<Map>(AssociationStrategies{}, assoc, scenario, options);
}

}  // namespace arbor

#define ARBOR_INSTANTIATE_FILTERS(Map)                                                                    \
  template std::unique_ptr<::arbor::Filter> arbor::make_filter_for_map<Map>(                             \
      std::string_view, const ::arbor::Scenario&, const ::arbor::FastSlamOptions&);

#endif  // ARBOR_VARIANTS_REGISTRY_IMPL_H_
