// Association decisions scored against ground-truth ids: precision, recall and F1 (DESIGN.md §7).
#ifndef ARBOR_CORE_METRICS_ASSOCIATION_SCORE_H_
#define ARBOR_CORE_METRICS_ASSOCIATION_SCORE_H_

#include <cstdint>
#include <optional>

namespace arbor {

// Counts of decisions over a run, for measurements whose true landmark (or clutter) is known.
//   true match:   paired with a landmark created from the same true landmark;
//   false match:  paired with a landmark of another true landmark, or with one created from clutter, or a
//                 clutter measurement paired with anything;
//   missed match: not paired although a landmark of the same true landmark was a candidate;
//   false new:    started a landmark although one of the same true landmark was a candidate, or from clutter.
struct AssociationCounts {
  std::int64_t true_matches = 0;
  std::int64_t false_matches = 0;
  std::int64_t missed_matches = 0;
  std::int64_t false_new = 0;
  std::int64_t scored = 0;  // measurements with ground truth

  AssociationCounts& operator+=(const AssociationCounts& o) {
    true_matches += o.true_matches;
    false_matches += o.false_matches;
    missed_matches += o.missed_matches;
    false_new += o.false_new;
    scored += o.scored;
    return *this;
  }
  // nullopt where undefined (no ground truth, or no decision of the kind).
  std::optional<double> precision() const {
    const auto d = true_matches + false_matches;
    return scored == 0 || d == 0 ? std::nullopt : std::optional<double>(double(true_matches) / d);
  }
  std::optional<double> recall() const {
    const auto d = true_matches + missed_matches;
    return scored == 0 || d == 0 ? std::nullopt : std::optional<double>(double(true_matches) / d);
  }
  std::optional<double> f1() const {
    const auto p = precision(), r = recall();
    if (!p || !r || *p + *r == 0.0) return std::nullopt;
    return 2.0 * *p * *r / (*p + *r);
  }
};

}  // namespace arbor

#endif  // ARBOR_CORE_METRICS_ASSOCIATION_SCORE_H_
