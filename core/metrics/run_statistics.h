// Summary statistics: quantiles and medians of samples, and the process's peak resident memory.
#ifndef ARBOR_CORE_METRICS_RUN_STATISTICS_H_
#define ARBOR_CORE_METRICS_RUN_STATISTICS_H_

#include <cstdint>
#include <vector>

namespace arbor {

// The q-quantile (0..1) by linear interpolation between order statistics; 0 for an empty sample.
double quantile(std::vector<double> values, double q);

// The median: the middle value, or the mean of the two middle ones; 0 for an empty sample. The same number
// as quantile(values, 0.5) but for rounding, in O(n) (the noise estimates are written with it).
double median(std::vector<double> values);

// Peak resident set size of this process so far, in bytes (getrusage).
std::int64_t peak_rss_bytes();

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_RUN_STATISTICS_H_
