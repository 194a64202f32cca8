// Known association: measurements are paired by the scenario's ground-truth ids (simulation, UTIAS), so the
// engine can be verified apart from any association error. The engine handles it directly.
#ifndef ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_
#define ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_

#include <string_view>

#include "core/association/association_problem.h"

namespace arbor {

class KnownAssociation {
 public:
  static constexpr std::string_view kName = "known";
  static constexpr bool kUsesGroundTruth = true;
  struct Scratch {};

  explicit KnownAssociation(const AssociationOptions&) {}
  // Never called by the engine (kUsesGroundTruth); declares every measurement new for standalone use.
  void solve(const AssociationProblem& problem, Scratch&, AssociationResult& result) const {
    result.pairing.assign(problem.measurements.size(), kNewLandmark);
    result.stats = {};
  }
};

static_assert(AssociationStrategy<KnownAssociation>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_
