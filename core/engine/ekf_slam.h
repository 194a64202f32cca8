// EKF-SLAM: one Gaussian over the pose and the whole map with its full joint covariance (Smith, Self &
// Cheeseman 1990; Probabilistic Robotics §10.2), the classic baseline beside FastSLAM. It shares FastSLAM's
// models and steps wherever the method allows, so a comparison measures the posterior's form and nothing
// else: the motion model's prediction with the same continuous-time noise, the range-bearing model, the
// association strategies (given the *joint* innovation covariance, with the pose-landmark and
// landmark-landmark correlations a particle's problem lacks), the inverse-model initialisation, and the
// existence evidence that confirms and prunes landmarks. Deterministic and serial: there is no sample and no
// map back end (the landmarks' metadata sit in a VectorMap-like Map only so the shared gathering and
// existence code can read them; the means and covariances there mirror the state after every scan).
#ifndef ARBOR_CORE_ENGINE_EKF_SLAM_H_
#define ARBOR_CORE_ENGINE_EKF_SLAM_H_

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "core/association/association_problem.h"
#include "core/check.h"
#include "core/engine/ekf_state.h"
#include "core/engine/existence.h"
#include "core/engine/fastslam_options.h"
#include "core/engine/map_concept.h"
#include "core/engine/particle.h"
#include "core/engine/scan_problem.h"
#include "core/engine/touched_landmark.h"
#include "core/types/scenario.h"

namespace arbor {

template <LandmarkMap Map, AssociationStrategy Assoc>
class EkfSlam {
 public:
  EkfSlam(const Scenario& scenario, const FastSlamOptions& options)
      : motion_(scenario.motion), R_(scenario.sensor.R()), scan_(scenario.sensor, options),
        existence_(options, !Assoc::kTraits.uses_ground_truth || options.prune_with_known_association),
        strategy_(options.association),
        state_(scenario.initial_pose, Mat3(scenario.initial_sigma.cwiseProduct(scenario.initial_sigma).asDiagonal())),
        last_time_s_(scenario.start_time_s) {
    history_.push({scenario.start_time_s, scenario.initial_pose});
  }

  // Predicts through the step's control; at a scan, associates with the joint innovation covariance,
  // updates every pairing in one batch, adds the new landmarks and keeps the existence evidence.
  void step(const ScenarioStep& step) {
    stats_ = StepStats{};
    stats_.n_eff = 1.0;
    state_.predict(motion_, step.control, motion_.body_noise(step.control, step.time_s - last_time_s_));
    last_time_s_ = step.time_s;
    if (step.has_scan) {
      state_.settle();
      scan(step);
    }
    if (step.has_scan || step.truth_pose) history_.push({step.time_s, state_.pose()});
    stats_.best_landmarks = map_.size();
    ++step_index_;
    scan_index_ += step.has_scan;
  }

  // Starts from a map known before the run (ids ascending, unique); new landmarks get ids above.
  void set_prior_map(const std::vector<Landmark>& landmarks) {
    ARBOR_CHECK(step_index_ == 0, "a prior map is set before the first step, not at step {}", step_index_);
    state_.reserve_landmarks(static_cast<int>(landmarks.size()));
    for (const Landmark& lm : landmarks) {
      state_.add_known_landmark(lm.id, lm.mean, lm.cov);
      map_.insert(lm);
      next_id_ = std::max<std::int64_t>(next_id_, std::int64_t{lm.id} + 1);
    }
    // The largest id the readers allow, 2^30 - 1, included: new landmarks take [2^30, 2^31 - 1].
    ARBOR_CHECK(next_id_ - 1 <= std::numeric_limits<LandmarkId>::max() / 2, "prior map landmark id {} leaves no ids for new landmarks",
                next_id_ - 1);
  }

  const StepStats& last_step_stats() const { return stats_; }
  PoseEstimate estimate() const { return {state_.pose(), state_.pose_covariance()}; }
  const EkfState& state() const { return state_; }
  const Map& map() const { return map_; }
  const PoseHistory& history() const { return history_; }
  const DecisionHistory& decisions() const { return decisions_; }
  std::int64_t rejected() const { return rejected_; }

 private:
  void scan(const ScenarioStep& step) {
    if (step.measurements.empty()) {
      apply_negative_evidence({});
      if (!erased_.empty()) decisions_.push(applied_removals(step_index_, erased_));
      return;
    }
    const Pose2 pose = state_.pose();
    scan_.begin_scan(step_index_, step.measurements);
    scan_.gather(map_, pose, state_.pose_covariance(), nullptr, &nearby_, &problem_);
    add_joint_covariance();
    strategy_.solve(problem_.problem, strategy_scratch_, result_);
    ARBOR_CHECK(result_.pairing.size() == step.measurements.size(), "strategy {} returned {} decisions for {} measurements",
                Assoc::kName, result_.pairing.size(), step.measurements.size());
    stats_.hypotheses = result_.stats.hypotheses;
    stats_.tests = result_.stats.tests;
    stats_.budget_exhausted = result_.stats.budget_exhausted;
    rejected_ += result_.stats.rejected;

    arbor::collect_touched(result_.pairing, map_, nearby_, &touched_, &touched_of_);
    update(step.measurements);
    for (std::size_t k = 0; k < step.measurements.size(); ++k) {
      const Measurement& m = step.measurements[k];
      if (touched_of_[k] >= 0) {
        Landmark& lm = touched_[touched_of_[k]].landmark;
        existence_.seen(&lm, scan_index_);
        if (!std::isnan(m.signature)) lm.signature = std::isnan(lm.signature) ? m.signature : lm.signature + 0.2f * (m.signature - lm.signature);
      } else if (result_.pairing[k] == kNewLandmark) {
        add_landmark(m, k);
      }
    }
    write_touched(touched_, Assoc::kTraits.reads_localities, &map_);
    mirror_state_into_map();
    apply_negative_evidence(touched_);
    decisions_.push(applied_decisions(step_index_, touched_, touched_of_, erased_));
  }

  // The joint covariance of every candidate's predicted measurement (2c x 2c, R on the diagonal blocks),
  // which replaces the problem's per-candidate S, H_pose and P (AssociationProblem::joint_covariance).
  void add_joint_covariance() {
    AssociationProblem& problem = problem_.problem;
    const int c = static_cast<int>(problem.candidates.size());
    jacobians_.resize(c);
    cross_.resize(c);
    for (int i = 0; i < c; ++i) {
      Jacobians& J = jacobians_[i];
      J.slot = state_.slot_of(problem.candidates[i].id);
      range_bearing_predict(state_.pose(), state_.landmark_mean(J.slot), &J.H_landmark, &J.H_pose);
      cross_[i] = state_.measurement_cross(J.slot, J.H_pose, J.H_landmark);
    }
    problem.joint_covariance.resize(2 * c, 2 * c);
    for (int i = 0; i < c; ++i)
      for (int j = 0; j <= i; ++j) {
        Mat2 block = state_.innovation_block(cross_[i], jacobians_[j].slot, jacobians_[j].H_pose, jacobians_[j].H_landmark);
        if (i == j) block = 0.5 * (block + block.transpose()) + R_;
        problem.joint_covariance.block<2, 2>(2 * i, 2 * j) = block;
        problem.joint_covariance.block<2, 2>(2 * j, 2 * i) = block.transpose();
      }
    for (int i = 0; i < c; ++i) {
      problem.candidates[i].S = problem.joint_covariance.block<2, 2>(2 * i, 2 * i);
      problem.candidates[i].H_pose.setZero();
    }
    problem.P.setZero();
  }

  // Every pairing of the scan in one batch update, with the innovations' covariance the association saw
  // (two measurements paired with one landmark share its prediction, but not their noise).
  void update(const std::vector<Measurement>& measurements) {
    const AssociationProblem& problem = problem_.problem;
    observations_.clear();
    candidate_of_.clear();
    for (std::size_t k = 0; k < measurements.size(); ++k) {
      const LandmarkId id = result_.pairing[k];
      if (id < 0) continue;
      const auto it = std::lower_bound(problem.candidates.begin(), problem.candidates.end(), id,
                                       [](const AssociationCandidate& c, LandmarkId v) { return c.id < v; });
      ARBOR_CHECK(it != problem.candidates.end() && it->id == id, "strategy {} paired with landmark {}, not a candidate", Assoc::kName, id);
      const int i = static_cast<int>(it - problem.candidates.begin());
      observations_.push_back({range_bearing_innovation(measurements[k].z(), it->z_hat), &cross_[i]});
      candidate_of_.push_back(i);
    }
    const int k = static_cast<int>(observations_.size());
    S_.resize(2 * k, 2 * k);
    for (int a = 0; a < k; ++a)
      for (int b = 0; b < k; ++b) {
        S_.block<2, 2>(2 * a, 2 * b) = problem.joint_covariance.block<2, 2>(2 * candidate_of_[a], 2 * candidate_of_[b]);
        if (a != b && candidate_of_[a] == candidate_of_[b]) S_.block<2, 2>(2 * a, 2 * b) -= R_;
      }
    state_.update(observations_, S_);
  }

  // A landmark started by measurement k (after the scan's update, as FastSLAM starts them at the drawn pose).
  void add_landmark(const Measurement& m, std::size_t k) {
    ARBOR_CHECK(next_id_ < std::numeric_limits<LandmarkId>::max(), "landmark ids are exhausted");
    Landmark lm;
    lm.id = static_cast<LandmarkId>(next_id_++);
    state_.add_landmark(lm.id, m.z(), R_);
    existence_.start(&lm, scan_index_);
    lm.signature = m.signature;
    lm.truth_label = m.truth_id >= 0 ? m.truth_id : -1;
    touched_of_[k] = static_cast<int>(touched_.size());
    touched_.push_back({lm, true});
  }

  // The state's means and marginal covariances, copied into the landmarks' records.
  void mirror_state_into_map() {
    for (int slot = 0; slot < state_.landmarks(); ++slot) {
      const Landmark* held = map_.find(state_.id(slot));
      ARBOR_CHECK(held != nullptr, "EKF landmark {} has no record", state_.id(slot));
      Landmark lm = *held;
      lm.mean = state_.landmark_mean(slot);
      lm.cov = state_.landmark_covariance(slot);
      map_.set(lm);
    }
  }

  // Existence evidence at the updated pose (core/engine/existence.h); a landmark it drops is marginalised out.
  void apply_negative_evidence(std::span<const TouchedLandmark> touched) {
    scan_.gather_nearby(map_, state_.pose(), 0.0, &nearby_);
    existence_.miss_unseen(nearby_, touched, state_.pose(), scan_index_, scan_.view(), nullptr, &map_, &erased_);
    state_.remove(erased_);
  }

  struct Jacobians {
    int slot = 0;
    Mat23 H_pose;
    Mat2 H_landmark;
  };

  MotionModel motion_;
  Mat2 R_;
  ScanProblem<Assoc::kTraits.uses_ground_truth> scan_;
  ExistenceEvidence existence_;
  Assoc strategy_;
  EkfState state_;
  Map map_;  // every landmark's record (existence, signature, locality), its mean and covariance the state's
  PoseHistory history_;
  DecisionHistory decisions_;
  double last_time_s_ = 0.0;
  std::int64_t next_id_ = 0;
  std::int64_t rejected_ = 0;
  std::int64_t step_index_ = 0;
  std::int32_t scan_index_ = 0;
  StepStats stats_;
  // One scan's working memory, kept between scans.
  std::vector<Landmark> nearby_;
  ScanProblemScratch problem_;
  typename Assoc::Scratch strategy_scratch_;
  AssociationResult result_;
  std::vector<TouchedLandmark> touched_;
  std::vector<int> touched_of_;
  std::vector<LandmarkId> erased_;
  std::vector<Jacobians> jacobians_;
  std::vector<MeasurementCross> cross_;  // per candidate: its rows H P, for the joint covariance and the update
  std::vector<EkfObservation> observations_;
  std::vector<int> candidate_of_;
  Eigen::MatrixXd S_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_EKF_SLAM_H_
