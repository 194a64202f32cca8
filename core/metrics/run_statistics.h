// Summary statistics of a run: time per step (median, p95) and the process's peak resident memory.
#ifndef ARBOR_CORE_METRICS_RUN_STATISTICS_H_
#define ARBOR_CORE_METRICS_RUN_STATISTICS_H_

#include <cstdint>
#include <vector>

namespace arbor {

// The q-quantile (0..1) by linear interpolation between order statistics; 0 for an empty sample.
double quantile(std::vector<double> values, double q);

// Peak resident set size of this process so far, in bytes (getrusage).
std::int64_t peak_rss_bytes();

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_RUN_STATISTICS_H_
