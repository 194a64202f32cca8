// A scan's working copies of the landmarks it pairs or starts: gathered once from the particle's map after the
// association, updated by the engine and its policies (loop closing, relocalisation), written back once.
#ifndef ARBOR_CORE_ENGINE_TOUCHED_LANDMARK_H_
#define ARBOR_CORE_ENGINE_TOUCHED_LANDMARK_H_

#include <algorithm>
#include <cstdint>
#include <span>
#include <vector>

#include "core/check.h"
#include "core/engine/map_concept.h"
#include "core/types/landmark.h"
#include "core/types/step_decisions.h"

namespace arbor {

// A working copy of a landmark the scan pairs (or starts), written back to the map once.
struct TouchedLandmark {
  Landmark landmark;
  bool is_new = false;
  bool was_confirmed = false;  // before this scan's update
};

inline bool touches(std::span<const TouchedLandmark> touched, LandmarkId id) {
  return std::any_of(touched.begin(), touched.end(), [&](const TouchedLandmark& t) { return t.landmark.id == id; });
}

// The landmark with this id as the map holds it now: from nearby (the landmarks gathered for the scan,
// ascending id) when it is there, a binary search instead of a second descent of the map, else from the map.
// Valid until the map is written.
template <LandmarkMap Map>
const Landmark* find_landmark(const Map& map, std::span<const Landmark> nearby, LandmarkId id) {
  const auto it = std::lower_bound(nearby.begin(), nearby.end(), id, [](const Landmark& lm, LandmarkId v) { return lm.id < v; });
  return it != nearby.end() && it->id == id ? &*it : map.find(id);
}

// *touched: a working copy of every landmark the decisions pair, once each; *touched_of: per measurement, its
// index there or -1.
template <LandmarkMap Map>
void collect_touched(std::span<const LandmarkId> decision, const Map& map, std::span<const Landmark> nearby,
                     std::vector<TouchedLandmark>* touched, std::vector<int>* touched_of) {
  touched->clear();
  touched_of->assign(decision.size(), -1);
  for (std::size_t k = 0; k < decision.size(); ++k) {
    const LandmarkId id = decision[k];
    if (id < 0) continue;
    int t = 0;
    while (t < static_cast<int>(touched->size()) && (*touched)[t].landmark.id != id) ++t;
    if (t == static_cast<int>(touched->size())) {
      const Landmark* lm = find_landmark(map, nearby, id);
      ARBOR_CHECK(lm != nullptr, "association paired with landmark {} that the map does not hold", id);
      touched->push_back({*lm, false, lm->confirmed});
    }
    (*touched_of)[k] = t;
  }
}

// Locality (Ge & Lewis 2006, ch. 9): everything observed in this scan was seen together. Then the map is
// written, once per touched landmark. The sets cost O(m^2) per scan and particle (11 % of a step with
// known association and 1000 particles), so they are kept only where something reads them (keep_localities).
template <LandmarkMap Map>
void write_touched(std::vector<TouchedLandmark>& touched, bool keep_localities, Map* map) {
  if (keep_localities)
    for (auto& a : touched)
      for (const auto& b : touched)
        if (a.landmark.id != b.landmark.id) a.landmark.locality.add(b.landmark.id);
  for (const auto& t : touched) {
    if (t.is_new) map->insert(t.landmark);
    else map->set(t.landmark);
  }
}

// What the scan did to the map, for the particle's DecisionHistory: per measurement the landmark it updated
// or started (kNoLandmark: none), and the landmarks the negative evidence erased.
inline StepDecisions applied_decisions(std::int64_t step, std::span<const TouchedLandmark> touched,
                                       std::span<const int> touched_of, const std::vector<LandmarkId>& erased) {
  StepDecisions applied{step, StepDecisions::Ids(touched_of.size(), kNoLandmark), {erased.begin(), erased.end()}};
  for (std::size_t k = 0; k < touched_of.size(); ++k)
    if (touched_of[k] >= 0) applied.landmarks[k] = touched[touched_of[k]].landmark.id;
  return applied;
}
// A scan that paired nothing but erased landmarks.
inline StepDecisions applied_removals(std::int64_t step, const std::vector<LandmarkId>& erased) {
  return {step, {}, {erased.begin(), erased.end()}};
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_TOUCHED_LANDMARK_H_
