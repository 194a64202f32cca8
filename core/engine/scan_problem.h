// Each particle's association problem for one scan (DESIGN.md §4): the scan's measurements, built once per
// scan and shared by every particle, and the particle's candidates, the landmarks its sensor could see.
#ifndef ARBOR_CORE_ENGINE_SCAN_PROBLEM_H_
#define ARBOR_CORE_ENGINE_SCAN_PROBLEM_H_

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <vector>

#include "core/association/association_problem.h"
#include "core/engine/fastslam_options.h"
#include "core/engine/map_concept.h"
#include "core/engine/sensor_view.h"
#include "core/engine/set_spread.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/range_bearing_model.h"
#include "core/models/sensor_model.h"
#include "core/types/scenario.h"

namespace arbor {

// A thread's problem, and the step whose scan its measurements hold: copied once per scan and thread, never
// rebuilt per particle.
struct ScanProblemScratch {
  AssociationProblem problem;
  std::int64_t holds_step = -1;
};

// kGroundTruth: the strategy's traits ask for ground truth (StrategyTraits::uses_ground_truth). Only then do
// the measurements' truth ids and the candidates' truth labels enter the problem, and only then is every
// landmark that a measurement's id names a candidate, in view or not, in the query box or beyond it: the
// oracle must find the landmark an id names wherever the estimate puts it (were it left out, a second landmark
// would start for the same id). Every other strategy sees only what could be in view.
template <bool kGroundTruth>
class ScanProblem {
 public:
  ScanProblem(const SensorModel& sensor, const FastSlamOptions& options)
      : view_(sensor, options.view_margins), R_(sensor.R()), signature_sigma_(sensor.sigma_signature) {}

  const SensorView& view() const { return view_; }

  // Builds the measurements every particle's problem shares, once per scan.
  void begin_scan(std::int64_t step, const std::vector<Measurement>& measurements) {
    step_ = step;
    measurements_.clear();
    for (const Measurement& m : measurements)
      measurements_.push_back({m.z(), m.signature, kGroundTruth ? m.truth_id : kTruthUnknown});
    if constexpr (kGroundTruth) {
      // Every id measured so far names a landmark each particle has mapped (the oracle starts one at its first
      // sighting): the ids gather must find wherever the particle's drift has put them.
      std::vector<std::int32_t> seen;
      std::set_union(seen_ids_.begin(), seen_ids_.end(), scan_ids_.begin(), scan_ids_.end(), std::back_inserter(seen));
      seen.erase(std::unique(seen.begin(), seen.end()), seen.end());  // a scan can name an id twice
      seen_ids_ = std::move(seen);
      scan_ids_.clear();
      for (const Measurement& m : measurements) scan_ids_.push_back(m.truth_id);
      std::sort(scan_ids_.begin(), scan_ids_.end());
    }
  }

  // The problem's measurements, noise and pose covariance P; no candidates yet. A thread's problem copies the
  // measurements once per scan.
  void begin(const Mat3& P, ScanProblemScratch* s) const {
    if (s->holds_step != step_) {
      s->problem.measurements = measurements_;
      s->holds_step = step_;
    }
    begin_candidates(P, &s->problem);
  }
  void begin(const Mat3& P, AssociationProblem* problem) const {
    problem->measurements = measurements_;
    begin_candidates(P, problem);
  }

  // *nearby: every landmark in the query box around pose, ascending id (the map concept's visit order).
  template <LandmarkMap Map>
  void gather_nearby(const Map& map, const Pose2& pose, double extra_reach_m, std::vector<Landmark>* nearby) const {
    nearby->clear();
    map.visit_near(view_.query_box(pose, extra_reach_m), [&](const Landmark& lm) { nearby->push_back(lm); });
  }

  // Fills *nearby (every landmark in the query box) and the problem's candidates (those the sensor could see
  // from a pose drawn from N(pose, P): the view is widened by three standard deviations of P).
  template <LandmarkMap Map>
  void gather(const Map& map, const Pose2& pose, const Mat3& P, const SetSpread* spread, std::vector<Landmark>* nearby,
              ScanProblemScratch* s) const {
    const ViewMargin margin = uncertainty_margin(P);
    gather_nearby(map, pose, margin.range_m, nearby);
    begin(P, s);
    const BearingBound bound = bearing_bound(pose, margin);
    for (const Landmark& lm : *nearby) {
      // What cannot be a candidate is passed over before its prediction and innovation covariance are paid for
      // (a third of the step at 1000 particles went to candidates never read): the oracle reads only those its
      // measurements' ids name, and a landmark out of range is out of view whatever its bearing. The candidates
      // kept are the same, in the same order, computed the same way.
      if constexpr (kGroundTruth)
        if (!std::binary_search(scan_ids_.begin(), scan_ids_.end(), lm.truth_label)) continue;
      if (certainly_not_candidate(lm, pose, margin, bound)) continue;
      // The prediction decides the view first; the Jacobians, S and the copy are paid only for a candidate.
      const Vec2 z_hat = range_bearing_predict(pose, lm.mean);
      if (is_candidate(z_hat, margin)) fill_candidate(lm, pose, z_hat, spread, &s->problem.candidates.emplace_back());
    }
    if constexpr (kGroundTruth) add_named_beyond_the_box(map, pose, spread, s);
  }

  // FastSlamOptions::gate_covariance = set: the measurements a particle at pose with covariance P predicts for
  // the landmarks it could see, for SetSpread::reduce. Leaves *nearby empty.
  template <LandmarkMap Map>
  void predict(const Map& map, const Pose2& pose, const Mat3& P, std::vector<Landmark>* nearby,
               std::vector<SetSpread::PredictedMeasurement>* out) const {
    const ViewMargin margin = uncertainty_margin(P);
    gather_nearby(map, pose, margin.range_m, nearby);
    out->clear();
    const BearingBound bound = bearing_bound(pose, margin);
    for (const Landmark& lm : *nearby) {
      if (certainly_not_candidate(lm, pose, margin, bound)) continue;
      const Vec2 z_hat = range_bearing_predict(pose, lm.mean);
      if (is_candidate(z_hat, margin)) out->push_back({lm.id, z_hat});
    }
    nearby->clear();
  }

  // Landmark lm as an association candidate seen from pose, its gate widened by the set's spread (if any).
  AssociationCandidate candidate(const Landmark& lm, const Pose2& pose, const SetSpread* spread) const {
    AssociationCandidate c;
    fill_candidate(lm, pose, range_bearing_predict(pose, lm.mean), spread, &c);
    return c;
  }
  // The same, given z_hat = range_bearing_predict(pose, lm.mean), written in place (gather builds each
  // candidate where the problem keeps it: 208 bytes not copied).
  void fill_candidate(const Landmark& lm, const Pose2& pose, const Vec2& z_hat, const SetSpread* spread,
                      AssociationCandidate* out) const {
    AssociationCandidate& c = *out;
    Mat2 H_m;
    c.z_hat = z_hat;
    range_bearing_jacobians(pose, lm.mean, &H_m, &c.H_pose);
    c.id = lm.id;
    if constexpr (kGroundTruth) c.truth_label = lm.truth_label;
    c.S = H_m * lm.cov * H_m.transpose() + R_;
    if (spread)
      if (const Mat2* d = spread->spread(lm.id)) c.S += *d;
    c.position = lm.mean;
    c.position_cov = lm.cov;
    c.signature = lm.signature;
    c.locality = lm.locality;
  }

 private:
  // The oracle's candidates outside the query box: a measured id that an earlier scan named, and no landmark in
  // the box carries, names a landmark this particle mapped where its drift has since put it far away. Left
  // out, a second landmark would start for the id and the loop would never close. A whole-map pass, paid only
  // in that case.
  template <LandmarkMap Map>
  void add_named_beyond_the_box(const Map& map, const Pose2& pose, const SetSpread* spread, ScanProblemScratch* s) const {
    std::vector<std::int32_t> missing;
    const auto& candidates = s->problem.candidates;
    for (std::int32_t id : scan_ids_) {
      if (id < 0 || !std::binary_search(seen_ids_.begin(), seen_ids_.end(), id)) continue;
      if (!missing.empty() && missing.back() == id) continue;
      if (std::none_of(candidates.begin(), candidates.end(), [&](const AssociationCandidate& c) { return c.truth_label == id; }))
        missing.push_back(id);
    }
    if (missing.empty()) return;
    map.for_each([&](const Landmark& lm) {
      if (std::binary_search(missing.begin(), missing.end(), lm.truth_label))
        fill_candidate(lm, pose, range_bearing_predict(pose, lm.mean), spread, &s->problem.candidates.emplace_back());
    });
  }

  void begin_candidates(const Mat3& P, AssociationProblem* problem) const {
    problem->candidates.clear();
    problem->R = R_;
    problem->P = P;
    problem->signature_sigma = signature_sigma_;
  }

  bool is_candidate(const Vec2& z, const ViewMargin& margin) const { return kGroundTruth || view_.in_candidate_view(z, margin); }
  // is_candidate's verdict where the range or the bearing's cosine settles it, before the bearing's atan2 is
  // paid for: predicted_range is to the bit the range range_bearing_predict gives, and BearingBound rules out
  // only what the view's own test would. The oracle keeps every landmark, so it builds no bound.
  BearingBound bearing_bound(const Pose2& pose, const ViewMargin& margin) const {
    if constexpr (kGroundTruth) return BearingBound{};
    else return BearingBound(pose, view_.candidate_cos_bound(margin));
  }
  bool certainly_not_candidate(const Landmark& lm, const Pose2& pose, const ViewMargin& margin,
                               const BearingBound& bound) const {
    if constexpr (kGroundTruth) return false;
    const double range_m = predicted_range(pose, lm.mean);
    return !view_.in_candidate_range(range_m, margin) || bound.certainly_beyond(lm.mean, range_m);
  }

  SensorView view_;
  Mat2 R_;
  double signature_sigma_;
  std::int64_t step_ = -1;
  std::vector<AssociationMeasurement> measurements_;  // this scan's, shared by every particle's problem
  std::vector<std::int32_t> scan_ids_;  // kGroundTruth: the truth ids this scan's measurements name, sorted
  std::vector<std::int32_t> seen_ids_;  // kGroundTruth: the ids every earlier scan named, sorted and unique
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_SCAN_PROBLEM_H_
