// make_filter: walks the map back end list, then the strategy list, to build the named engine.
#include "variants/registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "core/io/input_error.h"

namespace arbor {
namespace {

template <class... Maps>
std::unique_ptr<Filter> make_with_map(TypeList<Maps...>, std::string_view map, std::string_view assoc,
                                      const Scenario& scenario, const FastSlamOptions& options) {
  std::unique_ptr<Filter> filter;
  ((map == Maps::kName && !filter ? (void)(filter = make_filter_for_map<Maps>(assoc, scenario, options)) : (void)0),
   ...);
  return filter;
}

bool contains(const std::vector<std::string>& list, std::string_view name) {
  for (const auto& n : list)
    if (n == name) return true;
  return false;
}

}  // namespace

std::unique_ptr<Filter> make_filter(std::string_view map, std::string_view assoc, const Scenario& scenario,
                                    const FastSlamOptions& options) {
  const bool ekf = options.version == FilterVersion::kEkf;
  if (!ekf && !contains(map_backend_names(), map))
    throw InputError("", 0, "map", fmt::format("unknown map back end '{}' (valid: {})", map, fmt::join(map_backend_names(), ", ")));
  if (!contains(association_names(), assoc))
    throw InputError("", 0, "assoc", fmt::format("unknown association strategy '{}' (valid: {})", assoc, fmt::join(association_names(), ", ")));
  const std::string why = options.validate();
  if (!why.empty()) throw InputError("", 0, "options", why);
  if (ekf) return make_ekf_filter(assoc, scenario, options);
  return make_with_map(MapBackends{}, map, assoc, scenario, options);
}

}  // namespace arbor
