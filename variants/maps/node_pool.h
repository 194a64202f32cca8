// Node allocation for the persistent map back ends: a pooled, thread-safe heap plus live-node counters that
// the leak tests and the memory benchmarks read.
#ifndef ARBOR_VARIANTS_MAPS_NODE_POOL_H_
#define ARBOR_VARIANTS_MAPS_NODE_POOL_H_

#include <atomic>
#include <cstddef>
#include <cstdint>

#include <tbb/scalable_allocator.h>

namespace arbor::internal {

// Allocates the nodes of one back end (Tag tells the back ends apart so each has its own counters).
//
// Why tbbmalloc and no free list of our own: particles are updated in parallel, and a node allocated by one
// thread is routinely freed by another (the particle that owned it was resampled away on another thread).
// scalable_malloc already keeps per-thread size-class bins and hands a foreign free back to its owner thread
// lazily, which is exactly the per-thread pool we would otherwise write; a second layer of free lists on top
// would only hide memory from it. Blocks are 16-byte aligned (Eigen's fixed-size types need it).
//
// The counters are relaxed atomics: they are statistics, read when the threads are quiescent (tests, stats).
template <class Tag>
class NodePool {
 public:
  static void* allocate(std::size_t bytes) {
    live_nodes_.fetch_add(1, std::memory_order_relaxed);
    live_bytes_.fetch_add(static_cast<std::int64_t>(bytes), std::memory_order_relaxed);
    void* p = scalable_aligned_malloc(bytes, 16);
    if (p == nullptr) [[unlikely]] throw std::bad_alloc();
    return p;
  }
  static void deallocate(void* p, std::size_t bytes) noexcept {
    live_nodes_.fetch_sub(1, std::memory_order_relaxed);
    live_bytes_.fetch_sub(static_cast<std::int64_t>(bytes), std::memory_order_relaxed);
    scalable_aligned_free(p);
  }
  // Nodes (bytes) allocated and not yet freed, over all maps of this back end.
  static std::int64_t live_nodes() { return live_nodes_.load(std::memory_order_relaxed); }
  static std::int64_t live_bytes() { return live_bytes_.load(std::memory_order_relaxed); }

 private:
  static inline std::atomic<std::int64_t> live_nodes_{0};
  static inline std::atomic<std::int64_t> live_bytes_{0};
};

// Intrusive reference count. Increments are relaxed (taking a new reference needs no ordering: the taker
// already holds one); the decrement is acq_rel so that the thread that frees a node sees every write made
// by the threads that dropped it before (the usual shared_ptr argument).
inline void ref_inc(std::atomic<std::uint32_t>& rc) { rc.fetch_add(1, std::memory_order_relaxed); }
// Returns true when this was the last reference. A count of 1 is ours alone (taking a reference needs one),
// so nobody can change it: that case skips the locked decrement. The acquire load pairs with the release of
// the other holders' decrements as fetch_sub's acquire would. (A freed write path is all such nodes.)
inline bool ref_dec(std::atomic<std::uint32_t>& rc) {
  return rc.load(std::memory_order_acquire) == 1 || rc.fetch_sub(1, std::memory_order_acq_rel) == 1;
}
// A node whose count is 1, reached through a path of such nodes from a map we own, is ours alone and may be
// written in place. acquire: pairs with the release of the decrement that made it unique.
inline bool ref_unique(const std::atomic<std::uint32_t>& rc) { return rc.load(std::memory_order_acquire) == 1; }

}  // namespace arbor::internal

#endif  // ARBOR_VARIANTS_MAPS_NODE_POOL_H_
