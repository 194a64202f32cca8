// Known association: each measurement is paired with the candidate whose truth label is the measurement's
// ground-truth id (simulation, UTIAS), so the engine can be verified apart from any association error. The
// ids are trusted, the measurements are not: a pairing outside the chi-square gate (pose and landmark
// uncertainty included) is refused as an outlier of the sensor and counted; clutter is spurious; an id with
// no candidate starts a landmark.
#ifndef ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_
#define ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_

#include <limits>
#include <string_view>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "core/math/ldlt_solve2.h"
#include "core/models/range_bearing_model.h"

namespace arbor {

class KnownAssociation {
 public:
  static constexpr std::string_view kName = "known";
  static constexpr StrategyTraits kTraits{.uses_ground_truth = true, .standalone = false};
  struct Scratch {};

  explicit KnownAssociation(const AssociationOptions& options)
      : gate_(options.known_gate_probability < 1.0 ? chi_square_quantile(options.known_gate_probability, 2)
                                                   : std::numeric_limits<double>::infinity()) {}

  void solve(const AssociationProblem& problem, Scratch&, AssociationResult& result) const {
    result.pairing.assign(problem.measurements.size(), kSpurious);
    result.stats = {};
    for (std::size_t k = 0; k < problem.measurements.size(); ++k) {
      const AssociationMeasurement& m = problem.measurements[k];
      if (m.truth_id < 0) continue;  // clutter is recognised as such
      int match = -1;
      for (int j = 0; j < static_cast<int>(problem.candidates.size()) && match < 0; ++j)
        if (problem.candidates[j].truth_label == m.truth_id) match = j;
      if (match < 0) {
        result.pairing[k] = kNewLandmark;
        continue;
      }
      ++result.stats.tests;
      const Vec2 nu = range_bearing_innovation(m.z, problem.candidates[match].z_hat);
      if (nu.dot(ldlt_solve2(problem.innovation_covariance(match, match), nu)) <= gate_)
        result.pairing[k] = problem.candidates[match].id;
      else
        ++result.stats.rejected;
    }
  }

 private:
  double gate_;
};

static_assert(AssociationStrategy<KnownAssociation>);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_KNOWN_ASSOCIATION_H_
