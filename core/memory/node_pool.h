// Node allocation for the persistent structures (the map back ends, the particles' histories): a pooled,
// thread-safe heap plus live-node counters that the leak tests and the memory benchmarks read.
#ifndef ARBOR_CORE_MEMORY_NODE_POOL_H_
#define ARBOR_CORE_MEMORY_NODE_POOL_H_

#include <atomic>
#include <cstddef>
#include <cstdint>

#include <tbb/scalable_allocator.h>

namespace arbor::internal {

// Allocates the nodes of one structure (Tag tells them apart so each has its own counters).
//
// Why tbbmalloc and no free list of our own: particles are updated in parallel, and a node allocated by one
// thread is routinely freed by another (the particle that owned it was resampled away on another thread).
// scalable_malloc already keeps per-thread size-class bins and hands a foreign free back to its owner thread
// lazily, which is exactly the per-thread pool we would otherwise write; a second layer of free lists on top
// would only hide memory from it. Blocks are 16-byte aligned (Eigen's fixed-size types need it).
//
// The counters are statistics, read when the threads are quiescent (tests, stats). Each thread keeps its own
// tally and writes it with a plain load and store: a shared counter needs a locked add, which on x86 also
// waits for every load before it, two per node allocated or freed, ~60 per tree set at 10^4 landmarks. Where
// the map stays in cache they were a third of a set's time (results/maps/4eb58b0ffc_vm_gcc-12.2.0). A reader
// sums the tallies; a thread's tally outlives the thread (what it allocated may be freed elsewhere, so only
// the sum means anything).
template <class Tag>
class NodePool {
 public:
  static void* allocate(std::size_t bytes) {
    Tally& t = mine();
    bump(t.nodes, 1);
    bump(t.bytes, static_cast<std::int64_t>(bytes));
    void* p = scalable_aligned_malloc(bytes, 16);
    if (p == nullptr) [[unlikely]] throw std::bad_alloc();
    return p;
  }
  static void deallocate(void* p, std::size_t bytes) noexcept {
    Tally& t = mine();
    bump(t.nodes, -1);
    bump(t.bytes, -static_cast<std::int64_t>(bytes));
    scalable_aligned_free(p);
  }
  // Nodes (bytes) allocated and not yet freed, over all maps of this back end.
  static std::int64_t live_nodes() { return sum(&Tally::nodes); }
  static std::int64_t live_bytes() { return sum(&Tally::bytes); }

 private:
  struct Tally {
    std::atomic<std::int64_t> nodes{0};
    std::atomic<std::int64_t> bytes{0};
    Tally* next = nullptr;
  };
  // Only the owning thread writes a tally, so a relaxed load and store cannot lose an update.
  static void bump(std::atomic<std::int64_t>& c, std::int64_t d) {
    c.store(c.load(std::memory_order_relaxed) + d, std::memory_order_relaxed);
  }
  static Tally& mine() {
    thread_local Tally* tally = nullptr;
    if (tally == nullptr) [[unlikely]] tally = enlist();
    return *tally;
  }
  // A new thread's tally joins the list (never removed; one per thread that ever touched this back end).
  static Tally* enlist() {
    Tally* t = new Tally;
    t->next = tallies_.load(std::memory_order_relaxed);
    while (!tallies_.compare_exchange_weak(t->next, t, std::memory_order_release, std::memory_order_relaxed)) {
    }
    return t;
  }
  static std::int64_t sum(std::atomic<std::int64_t> Tally::*field) {
    std::int64_t total = 0;
    for (const Tally* t = tallies_.load(std::memory_order_acquire); t != nullptr; t = t->next)
      total += (t->*field).load(std::memory_order_relaxed);
    return total;
  }

  static inline std::atomic<Tally*> tallies_{nullptr};
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

#endif  // ARBOR_CORE_MEMORY_NODE_POOL_H_
