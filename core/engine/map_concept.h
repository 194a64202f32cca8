// The LandmarkMap concept: what every map back end (variants/maps/) provides to the FastSLAM engine.
//
// Valid expressions (m: M, cm: const M, id: LandmarkId, lm: Landmark, box: Box2, f: callable):
//   M m;                      an empty map
//   M copy = cm;              the particle copy: must be the cheapest thing the back end can do
//   cm.find(id)               -> const Landmark* (nullptr when absent); valid until m is next modified
//   m.set(lm)                 replaces the landmark with id lm.id (which must exist); copies only what the
//                             map shares with other maps
//   m.insert(lm)              adds a landmark whose id is not present
//   m.erase(id)               -> bool: removes it if present
//   cm.size()                 -> std::size_t
//   cm.for_each(f)            calls f(const Landmark&) for every landmark in ascending id order
//   cm.visit_near(box, f)     calls f(const Landmark&) for every landmark whose mean lies in box, in ascending
//                             id order; persistent back ends touch O(log N + k) nodes, not N
//   cm.memory_stats()         -> MapMemoryStats
//   M::kName                  the back end's name on the command line
//
// Invariants (tests/maps/ checks them for every back end in the registry):
//   - persistence: after `M b = a;` no operation on b changes what a answers, and vice versa;
//   - ordering: for_each and visit_near hand out landmarks in ascending id order;
//   - agreement: every back end answers identically to VectorMap for the same sequence of calls;
//   - no leaks: the nodes a back end allocated are all freed when the last map sharing them dies.
#ifndef ARBOR_CORE_ENGINE_MAP_CONCEPT_H_
#define ARBOR_CORE_ENGINE_MAP_CONCEPT_H_

#include <concepts>
#include <cstddef>
#include <string_view>

#include "core/types/box2.h"
#include "core/types/landmark.h"

namespace arbor {

struct MapMemoryStats {
  std::size_t nodes = 0;         // nodes reachable from this map
  std::size_t bytes = 0;         // bytes of those nodes (payload and bookkeeping)
  std::size_t shared_nodes = 0;  // of those, nodes also referenced by another map (refcount > 1)
  std::size_t shared_bytes = 0;

  // Counts `nodes` nodes of `bytes` bytes in all, as shared or not.
  void add(std::size_t node_count, std::size_t byte_count, bool shared) {
    nodes += node_count;
    bytes += byte_count;
    if (shared) {
      shared_nodes += node_count;
      shared_bytes += byte_count;
    }
  }
  MapMemoryStats& operator+=(const MapMemoryStats& o) {
    nodes += o.nodes;
    bytes += o.bytes;
    shared_nodes += o.shared_nodes;
    shared_bytes += o.shared_bytes;
    return *this;
  }
};

template <class M>
concept LandmarkMap = std::copyable<M> && std::default_initializable<M> &&
    requires(M m, const M cm, LandmarkId id, const Landmark& lm, const Box2& box) {
      { cm.find(id) } -> std::same_as<const Landmark*>;
      m.set(lm);
      m.insert(lm);
      { m.erase(id) } -> std::same_as<bool>;
      { cm.size() } -> std::convertible_to<std::size_t>;
      cm.for_each([](const Landmark&) {});
      cm.visit_near(box, [](const Landmark&) {});
      { cm.memory_stats() } -> std::same_as<MapMemoryStats>;
      { M::kName } -> std::convertible_to<std::string_view>;
    };

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_MAP_CONCEPT_H_
