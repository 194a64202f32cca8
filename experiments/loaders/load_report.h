// What a loader dropped or tolerated, counted by kind, so that `arbor convert` can print it and tests can
// check it (e.g. UTIAS robot 1: 407 measurements of other robots, 1 unknown barcode).
#ifndef ARBOR_EXPERIMENTS_LOADERS_LOAD_REPORT_H_
#define ARBOR_EXPERIMENTS_LOADERS_LOAD_REPORT_H_

#include <cstdint>
#include <map>
#include <string>

namespace arbor {

struct LoadReport {
  std::map<std::string, std::int64_t> counts;  // e.g. "dropped: measurement of another robot" -> 407
  std::map<std::string, std::string> notes;    // estimated values and other facts worth printing

  void add(const std::string& what, std::int64_t n = 1) { counts[what] += n; }
  std::int64_t count(const std::string& what) const {
    const auto it = counts.find(what);
    return it == counts.end() ? 0 : it->second;
  }
};

}  // namespace arbor

#endif  // ARBOR_EXPERIMENTS_LOADERS_LOAD_REPORT_H_
