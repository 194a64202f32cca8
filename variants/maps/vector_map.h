// The naive map back end: a std::vector of landmarks sorted by id. Copying a map copies all N landmarks
// (O(N) per particle copy, the cost FastSLAM's tree was invented to avoid); find is a binary search and
// visit_near scans every landmark. The reference every other back end must agree with.
#ifndef ARBOR_VARIANTS_MAPS_VECTOR_MAP_H_
#define ARBOR_VARIANTS_MAPS_VECTOR_MAP_H_

#include <algorithm>
#include <string_view>
#include <vector>

#include "core/check.h"
#include "core/engine/map_concept.h"
#include "core/types/box2.h"

namespace arbor {

class VectorMap {
 public:
  static constexpr std::string_view kName = "naive";

  // O(log N), no allocation.
  [[nodiscard]] const Landmark* find(LandmarkId id) const {
    auto it = lower_bound(id);
    return it != landmarks_.end() && it->id == id ? &*it : nullptr;
  }
  // O(log N); the landmark must exist.
  void set(const Landmark& lm) {
    auto it = lower_bound(lm.id);
    ARBOR_CHECK(it != landmarks_.end() && it->id == lm.id, "set of absent landmark {}", lm.id);
    *it = lm;
  }
  // Amortised O(1) when ids arrive in increasing order (the engine's case), O(N) otherwise.
  void insert(const Landmark& lm) {
    auto it = lower_bound(lm.id);
    ARBOR_CHECK(it == landmarks_.end() || it->id != lm.id, "insert of existing landmark {}", lm.id);
    landmarks_.insert(it, lm);
  }
  // O(N): later landmarks shift down.
  bool erase(LandmarkId id) {
    auto it = lower_bound(id);
    if (it == landmarks_.end() || it->id != id) return false;
    landmarks_.erase(it);
    return true;
  }
  [[nodiscard]] std::size_t size() const { return landmarks_.size(); }

  template <class F>
  void for_each(F&& f) const {
    for (const Landmark& lm : landmarks_) f(lm);
  }
  // O(N): a scan, by design.
  template <class F>
  void visit_near(const Box2& box, F&& f) const {
    for (const Landmark& lm : landmarks_)
      if (box.contains(lm.mean)) f(lm);
  }
  // Nothing is shared between copies.
  [[nodiscard]] MapMemoryStats memory_stats() const {
    return {1, sizeof(*this) + landmarks_.capacity() * sizeof(Landmark), 0, 0};
  }

 private:
  std::vector<Landmark>::const_iterator lower_bound(LandmarkId id) const {
    return std::lower_bound(landmarks_.begin(), landmarks_.end(), id,
                            [](const Landmark& lm, LandmarkId key) { return lm.id < key; });
  }
  std::vector<Landmark>::iterator lower_bound(LandmarkId id) {
    return std::lower_bound(landmarks_.begin(), landmarks_.end(), id,
                            [](const Landmark& lm, LandmarkId key) { return lm.id < key; });
  }
  std::vector<Landmark> landmarks_;
};

static_assert(LandmarkMap<VectorMap>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_MAPS_VECTOR_MAP_H_
