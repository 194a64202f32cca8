// Definition of make_filter_for_map; included only by the per-back-end instantiation files.
#ifndef ARBOR_VARIANTS_REGISTRY_IMPL_H_
#define ARBOR_VARIANTS_REGISTRY_IMPL_H_

#include "variants/association/locality_relocalizer.h"
#include "variants/registry.h"

namespace arbor {

template <LandmarkMap Map>
std::unique_ptr<Filter> make_filter_for_map(std::string_view assoc, const Scenario& scenario,
                                            const FastSlamOptions& options) {
  return make_for_strategy(AssociationStrategies{}, assoc, [&]<class S>() -> std::unique_ptr<Filter> {
    return std::make_unique<FilterImpl<Map, S>>(
        scenario, options, options.relocalize ? make_locality_relocalizer(options.association) : Relocalizer{});
  });
}

}  // namespace arbor

#define ARBOR_INSTANTIATE_FILTERS(Map)                                                                    \
  template std::unique_ptr<::arbor::Filter> arbor::make_filter_for_map<Map>(                             \
      std::string_view, const ::arbor::Scenario&, const ::arbor::FastSlamOptions&);

#endif  // ARBOR_VARIANTS_REGISTRY_IMPL_H_
