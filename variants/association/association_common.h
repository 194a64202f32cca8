// Pieces every association strategy shares: individual chi-square gating, the canonical (input-order free)
// measurement order, and the one rule that decides what an unpaired measurement becomes (NEW or SPURIOUS).
#ifndef ARBOR_VARIANTS_ASSOCIATION_ASSOCIATION_COMMON_H_
#define ARBOR_VARIANTS_ASSOCIATION_ASSOCIATION_COMMON_H_

#include <cstdint>
#include <limits>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/eigen_types.h"

namespace arbor::association {

// Marks a measurement not yet decided; finish_unpaired() replaces it with kNewLandmark or kSpurious.
inline constexpr LandmarkId kUnassigned = std::numeric_limits<LandmarkId>::min();

// One individually compatible (measurement, candidate) pair: d2 = nu^T C_jj^-1 nu within the gate, where
// C_jj = innovation_covariance(j, j) includes the pose part H_j P H_j^T.
struct GatedPair {
  double d2;
  int measurement;  // index into problem.measurements
  int candidate;    // index into problem.candidates
};

// Per-measurement facts from the individual gating pass.
struct IndividualGating {
  std::vector<GatedPair> pairs;  // all pairs inside the gate, grouped by measurement, candidates ascending
  std::vector<int> first;        // pairs of measurement i are pairs[first[i] .. first[i + 1])
  std::vector<char> near_any;    // measurement i lies inside the new-landmark gate of some candidate
  std::vector<Mat2> inverse;     // C_jj^-1 per candidate (buffer)
  std::vector<char> valid;       // C_jj was positive definite
  std::vector<double> reach2;    // squared range innovation past which candidate j is outside both gates
};

// Gates every (measurement, candidate) pair: O(m n) 2x2 Mahalanobis distances, counted in stats->tests.
// gate and new_landmark_gate are chi-square thresholds with 2 dof.
void gate_individually(const AssociationProblem& problem, double gate, double new_landmark_gate,
                       IndividualGating* gating, AssociationStats* stats);

// Mutual exclusion resolved greedily: *pairs sorted (in place) by (Mahalanobis distance, landmark id, the
// measurement's rank in the canonical order), each pair accepted when its measurement is still kUnassigned
// in *pairing and its candidate not yet taken. The order makes the answer independent of the input order.
void pair_greedily(const AssociationProblem& problem, const std::vector<int>& rank, std::vector<GatedPair>* pairs,
                   std::vector<char>* taken, std::vector<LandmarkId>* pairing);

// Indices of the measurements sorted by (range, bearing, signature, index): the order every tree search uses,
// so the answer does not depend on the order of the input (the index only separates exact duplicates).
void canonical_measurement_order(const AssociationProblem& problem, std::vector<int>* order);

// The shared unpaired rule (DESIGN.md §4): a measurement left unpaired starts a new landmark only when it is
// outside the new-landmark gate of every candidate; otherwise it is ambiguous (it may be a noisy view of a
// known landmark, or clutter), and starting a landmark there would make a duplicate, so it is SPURIOUS.
inline void finish_unpaired(const std::vector<char>& near_any, std::vector<LandmarkId>* pairing) {
  for (std::size_t i = 0; i < pairing->size(); ++i)
    if ((*pairing)[i] == kUnassigned) (*pairing)[i] = near_any[i] ? kSpurious : kNewLandmark;
}

// Whether a 2x2 symmetric matrix is positive definite (Sylvester's criterion), the test invert_spd2 makes.
inline bool is_spd2(const Mat2& a) {
  const double det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  return a(0, 0) > 0.0 && det > 0.0;
}

// Inverse of a 2x2 SPD matrix; false when it is not positive definite (degenerate covariance).
inline bool invert_spd2(const Mat2& a, Mat2* inverse) {
  if (!is_spd2(a)) return false;
  const double det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
  *inverse << a(1, 1) / det, -a(0, 1) / det, -a(1, 0) / det, a(0, 0) / det;
  return true;
}

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_ASSOCIATION_COMMON_H_
