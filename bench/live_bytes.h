// Bytes a map back end's node pool holds right now, for the benchmarks' memory counters.
#ifndef ARBOR_BENCH_LIVE_BYTES_H_
#define ARBOR_BENCH_LIVE_BYTES_H_

#include <cstdint>

namespace arbor::bench {

// M::live_bytes() where the back end counts its allocations, else -1.
template <class M>
std::int64_t live_bytes() {
  if constexpr (requires { M::live_bytes(); }) return M::live_bytes();
  else return -1;
}

}  // namespace arbor::bench

#endif  // ARBOR_BENCH_LIVE_BYTES_H_
