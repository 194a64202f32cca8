// The one list of filters. Each entry's traits say what a run of it is made of, and the callers read the
// traits, never a filter's name: `arbor run --filter` offers the online filters, a sweep grid checks its
// filter names here, builds a run's key and its command line from the traits, and asks only for the grid
// dimensions (map, assoc, particles) some listed filter uses. A new filter is one entry here (and, for an
// online one, its engine behind make_filter in variants/registry.cc).
#ifndef ARBOR_VARIANTS_FILTER_LIST_H_
#define ARBOR_VARIANTS_FILTER_LIST_H_

#include <algorithm>
#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "core/check.h"

namespace arbor {

struct FilterTraits {
  bool has_particles = false;        // a run takes --particles (a sample-based posterior)
  bool has_map_backends = false;     // a run takes --map: its map lives in one of the interchangeable back ends
  bool chooses_association = false;  // a run takes --assoc; otherwise it is given the scenario's ids
  bool is_batch = false;  // solves the whole run at once (`arbor smooth`); takes none of `arbor run`'s options
};

struct FilterEntry {
  std::string_view name;
  std::string_view summary;  // one line for --help
  FilterTraits traits;
  std::string_view command;  // the `arbor` subcommand that runs it
};

inline constexpr std::array kFilters{
    FilterEntry{"fastslam1", "FastSLAM 1.0: particles sampled from the motion model", {true, true, true, false}, "run"},
    FilterEntry{"fastslam2",
                "FastSLAM 2.0: particles drawn from the measurement-informed proposal",
                {true, true, true, false},
                "run"},
    FilterEntry{"ekf",
                "EKF-SLAM: one Gaussian over pose and map with the full joint covariance, O(N^2) an update; "
                "deterministic, no particles and no map back end",
                {false, false, true, false},
                "run"},
    FilterEntry{"smoother",
                "Ceres full-SLAM least squares over the whole run, known association",
                {false, false, false, true},
                "smooth"},
};

// The entry named `name`, or nullptr.
inline const FilterEntry* find_filter(std::string_view name) {
  const auto* it = std::find_if(kFilters.begin(), kFilters.end(), [&](const FilterEntry& f) { return f.name == name; });
  return it == kFilters.end() ? nullptr : it;
}

// The entry of a filter whose name was already checked against the list (a sweep spec's, a result row's).
inline const FilterEntry& listed_filter(std::string_view name) {
  const FilterEntry* entry = find_filter(name);
  ARBOR_CHECK(entry, "'{}' is not in variants/filter_list.h", name);
  return *entry;
}

// The names of the filters whose traits satisfy keep(traits), in list order.
template <class Keep>
std::vector<std::string> filter_names_where(Keep keep) {
  std::vector<std::string> names;
  for (const FilterEntry& f : kFilters)
    if (keep(f.traits)) names.emplace_back(f.name);
  return names;
}
inline std::vector<std::string> filter_names() {
  return filter_names_where([](const FilterTraits&) { return true; });
}
inline std::vector<std::string> online_filter_names() {  // what `arbor run --filter` runs
  return filter_names_where([](const FilterTraits& t) { return !t.is_batch; });
}

}  // namespace arbor

#endif  // ARBOR_VARIANTS_FILTER_LIST_H_
