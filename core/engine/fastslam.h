// The FastSLAM engine: a Rao-Blackwellised particle filter whose particles each carry a pose sample and a
// map of independent 2x2 landmark EKFs (Montemerlo, Thrun, Koller & Wegbreit 2002: FastSLAM 1.0; Montemerlo,
// Thrun, Koller & Wegbreit 2003: FastSLAM 2.0). Templated on the map back end and the association strategy;
// per-particle work runs in tbb::parallel_for, everything that combines particles runs serially in particle
// order, and all randomness comes from counter-based streams, so a run is bit-identical for any thread count
// and any map back end. This file holds the paper's steps; the options that extend them are policies beside
// it, held only when switched on: relocalisation, loop closing, resample-move and set gating.
#ifndef ARBOR_CORE_ENGINE_FASTSLAM_H_
#define ARBOR_CORE_ENGINE_FASTSLAM_H_

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/association/association_problem.h"
#include "core/check.h"
#include "core/engine/existence.h"
#include "core/engine/fastslam_options.h"
#include "core/engine/landmark_ekf.h"
#include "core/engine/loop_closing.h"
#include "core/engine/map_concept.h"
#include "core/engine/measurement_likelihood.h"
#include "core/engine/particle.h"
#include "core/engine/relocalization.h"
#include "core/engine/resample_move.h"
#include "core/engine/resampling.h"
#include "core/engine/rng.h"
#include "core/engine/scan_problem.h"
#include "core/engine/set_spread.h"
#include "core/engine/touched_landmark.h"
#include "core/math/chi_square.h"
#include "core/models/composed_motion.h"
#include "core/models/motion_model.h"
#include "core/models/range_bearing_model.h"
#include "core/types/scenario.h"

namespace arbor {

template <LandmarkMap Map, AssociationStrategy Assoc>
class FastSlam {
 public:
  // relocalizer: needed (non-empty) when options.relocalize is set.
  FastSlam(const Scenario& scenario, const FastSlamOptions& options, Relocalizer relocalizer = {})
      : options_(options), motion_(scenario.motion), R_(scenario.sensor.R()), scan_(scenario.sensor, options),
        likelihood_(options.likelihood, options.student_dof), ekf_(R_, likelihood_),
        existence_(options, !Assoc::kTraits.uses_ground_truth || options.prune_with_known_association),
        strategy_(options.association), arena_(options.threads > 0 ? options.threads : tbb::task_arena::automatic) {
    const std::string why = options.validate();
    ARBOR_CHECK(why.empty(), "{}", why);
    ARBOR_CHECK(options.version != FilterVersion::kEkf, "EKF-SLAM is core/engine/ekf_slam.h, not this engine");
    ARBOR_CHECK(!options.relocalize || relocalizer, "relocalize is set but no relocalizer was given");
    const Mat2 typical_innovation = 2.0 * R_;  // a fresh landmark's innovation covariance is about 2R
    const double gate = chi_square_quantile(options.association.gate_probability, 2);
    log_likelihood_unpaired_ = -0.5 * gate - std::log(2.0 * kPi) - 0.5 * std::log(typical_innovation.determinant());
    weight_exponent_ = options.effective_weight_exponent(Assoc::kTraits.uses_ground_truth);
    pose_from_confirmed_ = options.pose_from_confirmed && !Assoc::kTraits.uses_ground_truth;
    keep_localities_ = Assoc::kTraits.reads_localities || options.relocalize;  // the relocaliser's tree reads them
    if (options.relocalize) relocalization_.emplace(std::move(relocalizer), options.relocalize_min_pairings);
    if (options.close_loops && !Assoc::kTraits.uses_ground_truth)  // known association's ids close loops themselves
      loops_.emplace(options.loop_drift_m, gate, options.dormant_scans);
    if (options.gate_covariance == GateCovariance::kSet) set_spread_.emplace(options.particles);
    if (options.move_window > 0) moves_.emplace(options, weight_exponent_, ekf_);
    last_time_s_ = scenario.start_time_s;
    particles_.resize(options.particles);
    for (int i = 0; i < options.particles; ++i) start_particle(scenario, options.seed, i, &particles_[i]);
    weights_.assign(options.particles, 1.0 / options.particles);
  }

  // Processes one step: resample if the previous step left N_eff low, then predict and (with a scan)
  // associate, update and weight every particle.
  void step(const ScenarioStep& step) {
    stats_ = StepStats{};
    step_noise_ = motion_.body_noise(step.control, step.time_s - last_time_s_);  // shared by every particle
    last_time_s_ = step.time_s;
    if (step_index_ > 0 && last_n_eff_ < options_.resample_threshold * options_.particles) resample();
    const bool deferred = defers_prediction(step);  // then composed once for the set (composed_motion.h)
    if (deferred) pending_motion_.add(motion_, step.control, step_noise_);
    else predict_and_correct(step);
    // A deferred step leaves the weights as they were, unless it resampled (equal weights, N_eff = M).
    if (!deferred || stats_.resampled) last_n_eff_ = normalize_particle_weights(&particles_, &weights_, step_index_);
    stats_.n_eff = last_n_eff_;
    stats_.best_landmarks = particles_[best_particle()].map.size();
    if (relocalization_ && step.has_scan) relocalize_if_lost(step);
    ++step_index_;
    scan_index_ += step.has_scan;
  }

  // Starts every particle from the same prior map (start_from_prior_map, core/engine/particle.h).
  void set_prior_map(const Map& map) {
    ARBOR_CHECK(step_index_ == 0, "a prior map is set before the first step, not at step {}", step_index_);
    start_from_prior_map(map, &particles_);
  }

  const StepStats& last_step_stats() const { return stats_; }
  std::int64_t steps_done() const { return step_index_; }
  int particle_count() const { return static_cast<int>(particles_.size()); }
  // Particle i as of the last step that was not deferred; predicted_pose(i) adds the controls since.
  const Particle<Map>& particle(int i) const { return particles_[i]; }
  PosePrediction predicted_pose(int i) const {
    PosePrediction now{particles_[i].pose, particles_[i].pose_covariance};
    pending_motion_.apply(&now.pose, &now.pose_covariance);
    return now;
  }
  double weight(int i) const { return weights_[i]; }

  // The particle of highest weight (lowest index on ties).
  int best_particle() const {
    return static_cast<int>(std::max_element(weights_.begin(), weights_.end()) - weights_.begin());
  }

  // How far back the set can revise its path (paths_meet_time_s, core/engine/particle.h).
  std::optional<double> common_ancestor_time_s() const { return paths_meet_time_s(particles_); }

  PoseEstimate estimate() const {
    if (pending_motion_.empty()) return weighted_pose_estimate(particles_, weights_);  // no copies at a scan
    std::vector<PosePrediction> now(particles_.size());
    for (int i = 0; i < particle_count(); ++i) now[i] = predicted_pose(i);
    return weighted_pose_estimate(now, weights_);
  }

  // The landmarks particle i's resample-move window touched, replayed along the path it holds: equal to what
  // its map holds, which is how the tests check the move's bookkeeping.
  std::vector<LandmarkEstimate> replay_move_window(int i) const {
    return moves_ ? moves_->replay(particles_[i].move) : std::vector<LandmarkEstimate>{};
  }

  // Scans at which every particle was re-seeded at a relocalised pose.
  std::int64_t relocalizations() const { return relocalization_ ? relocalization_->relocalizations() : 0; }

  MapMemoryStats memory_stats() const { return summed_memory_stats(particles_); }

 private:
  // Particle plus per-step counters the serial reduction reads.
  struct ParticleState : Particle<Map> {
    AssociationStats step_search;  // this step's search (its rejected count is kept in Particle::rejected)
  };

  struct Scratch {
    std::vector<Landmark> nearby;              // landmarks in the query box, ascending id
    ScanProblemScratch problem;                // this particle's association problem
    AssociationResult result;
    typename Assoc::Scratch strategy;
    std::vector<LandmarkId> decision;          // per measurement
    std::vector<TouchedLandmark> touched;
    std::vector<int> touched_of;               // per measurement: index into touched, or -1
    std::vector<LandmarkId> erased;            // removed by this scan's negative evidence
    LoopClosingScan loops;                     // loop closing's redirections and retirements (when on)
    bool provisional_steers = false;           // FastSlamOptions::provisional_steer_min: they steer this scan
  };

  // What a scan shares between its particles, built once: its measurements as the association problems read
  // them (core/engine/scan_problem.h), and the relocalisation's per-scan counts.
  void begin_scan(const ScenarioStep& step) {
    scan_.begin_scan(step_index_, step.measurements);
    if (relocalization_) relocalization_->begin_scan(particle_count());
  }

  void resample() {
    const PoseEstimate set_before_resampling = options_.roughen > 0.0 ? estimate() : PoseEstimate{};
    RandomStream rng(options_.seed, step_index_, 0, RandomPurpose::kResample);
    const std::vector<int> parents = systematic_resample(weights_, rng.uniform());
    take_children(parents, &particles_, arena_);
    for (auto& p : particles_) p.log_weight = 0.0;
    weights_.assign(particles_.size(), 1.0 / particles_.size());
    stats_.resampled = true;
    if (options_.roughen > 0.0)
      roughening_kernel_ = roughening_kernel(options_.roughen, particle_count(), set_before_resampling.covariance);
    if (moves_) moves_->move_all(particles_, step_index_, arena_, &stats_.moves_proposed, &stats_.moves_accepted);
  }

  // Every particle through the step: predict, and at a scan associate, update and weight.
  void predict_and_correct(const ScenarioStep& step) {
    if (step.has_scan) begin_scan(step);
    // A step between scans only predicts: chunks of 512 keep the scheduling from costing more than the work.
    const int grain = !step.has_scan && options_.motion_sampling == MotionSampling::kPerScan ? 512 : 1;
    const auto for_each_particle = [&](int grain_size, const auto& f) {
      arena_.execute([&] {
        tbb::parallel_for(tbb::blocked_range<int>(0, static_cast<int>(particles_.size()), grain_size), [&](const auto& range) {
          Scratch& scratch = scratch_.local();
          for (int i = range.begin(); i != range.end(); ++i) f(particles_[i], i, scratch);
        });
      });
    };
    if (set_spread_ && step.has_scan && !step.measurements.empty()) {
      // The set's spread needs every particle's prediction first: two passes with a serial reduction between.
      for_each_particle(1, [&](ParticleState& p, int i, Scratch& s) {
        predict_particle(p, step, i);
        scan_.predict(p.map, p.pose, p.pose_covariance, &s.nearby, &set_spread_->predicted(i));
      });
      set_spread_->reduce(weights_);
      for_each_particle(1, [&](ParticleState& p, int i, Scratch& s) { correct_particle(p, step, i, s); });
      set_spread_->clear();
    } else {
      for_each_particle(grain, [&](ParticleState& p, int i, Scratch& s) {
        predict_particle(p, step, i);
        correct_particle(p, step, i, s);
      });
    }
    roughening_kernel_.reset();
    pending_motion_.clear();
    for (const ParticleState& p : particles_) {
      stats_.hypotheses += p.step_search.hypotheses;
      stats_.tests += p.step_search.tests;
      stats_.budget_exhausted += p.step_search.budget_exhausted;
    }
  }

  // One particle's step, along Montemerlo et al. 2003 (FastSLAM 2.0, §3-4), in two parts: predict through
  // the control; then, at a scan, associate, propose and draw the pose, update and create landmarks, weight,
  // and keep the existence evidence. Between scans (per-scan sampling) only the prediction runs.
  void predict_particle(ParticleState& p, const ScenarioStep& step, int index) const {
    p.step_search = {};
    pending_motion_.apply(&p.pose, &p.pose_covariance);
    if (roughening_kernel_) p.pose_covariance += *roughening_kernel_;
    motion_.predict(&p.pose, &p.pose_covariance, step.control, step_noise_);
    if (moves_ && step.has_scan) ResampleMove::predicted(p.pose, p.pose_covariance, &p.move);
    // FastSLAM 1.0 draws first and associates at the sample (P = 0); 2.0 associates at the prediction with
    // its covariance, because its proposal is drawn only after association (DESIGN.md §4).
    if (options_.version == FilterVersion::kFastSlam1 && step.has_scan && !step.measurements.empty())
      draw_pose(p, index, RandomPurpose::kMotion);
  }

  void correct_particle(ParticleState& p, const ScenarioStep& step, int index, Scratch& s) {
    const bool fastslam2 = options_.version == FilterVersion::kFastSlam2;
    const bool per_control = options_.motion_sampling == MotionSampling::kPerControl;
    if (!step.has_scan || step.measurements.empty()) {
      if (step.has_scan || per_control) draw_pose(p, index, RandomPurpose::kMotion);
      if (step.has_scan) {
        scan_.gather_nearby(p.map, p.pose, 0.0, &s.nearby);
        apply_negative_evidence(p, s, /*touched=*/{});
        if (!s.erased.empty()) p.decisions.push(applied_removals(step_index_, s.erased));
      }
      record_pose(p, step);
      if (moves_ && step.has_scan) moves_->record(drawn_scan(p.move, p.pose, {}, {}, {}, nullptr), &p.move);
      return;
    }
    scan_.gather(p.map, p.pose, p.pose_covariance, spread(), &s.nearby, &s.problem);
    decide(p, step, s);
    if (loops_) loops_->redirect(p.aliases, [&](LandmarkId id) { return find_landmark(p.map, s.nearby, id); }, &s.decision, &s.loops);
    collect_touched(p, s);
    std::vector<LandmarkEstimate> before = moves_ ? estimates_before(s.touched) : std::vector<LandmarkEstimate>{};
    if (relocalization_) relocalization_->count_pairings(index, s.touched, s.touched_of, scan_index_);
    double log_weight = fastslam2 ? propose_and_draw(p, step.measurements, index, s) : 0.0;
    log_weight += update_landmarks(p, step.measurements, s, /*weight=*/!fastslam2);
    log_weight += add_new_landmarks(p, step.measurements, s);
    if (loops_) loops_->find_aliases(s.touched, s.nearby, scan_index_, &p.aliases, &p.loop_closures);
    write_touched(s.touched, keep_localities_, &p.map);  // locality sets only where something reads them
    apply_negative_evidence(p, s, s.touched);
    p.log_weight += weight_exponent_ * log_weight;  // FastSlamOptions::weight_exponent
    record_pose(p, step);
    p.decisions.push(applied_decisions(step_index_, s.touched, s.touched_of, s.erased));
    if (moves_) moves_->record(drawn_scan(p.move, p.pose, std::move(before), s.touched, s.touched_of, &step.measurements), &p.move);
  }

  // A step that only predicts, records no pose and has no policy reading the poses between scans is folded
  // into pending_motion_ (core/models/composed_motion.h).
  bool defers_prediction(const ScenarioStep& step) const {
    return !step.has_scan && !step.truth_pose && options_.motion_sampling == MotionSampling::kPerScan &&
           !roughening_kernel_ && !moves_;
  }

  // Replaces the prediction N(pose, P) by one draw from it.
  void draw_pose(ParticleState& p, int index, RandomPurpose purpose) const {
    RandomStream rng(options_.seed, step_index_, index, purpose);
    p.pose = Pose2::from_vector(sample_gaussian(p.pose.vector(), p.pose_covariance, rng));
    p.pose_covariance.setZero();
  }

  void record_pose(ParticleState& p, const ScenarioStep& step) const {
    if (!step.has_scan && !step.truth_pose.has_value()) return;
    p.history.push({step.time_s, p.pose});
    p.move.history_entries_since_draw += moves_ && !step.has_scan;
  }

  // The scan's working copies of the landmarks it pairs (core/engine/touched_landmark.h), and whether its
  // provisional pairings steer it (FastSlamOptions::provisional_steer_min: every pairing of the scan is
  // provisional, and there are enough).
  void collect_touched(const ParticleState& p, Scratch& s) const {
    arbor::collect_touched(s.decision, p.map, s.nearby, &s.touched, &s.touched_of);
    const int min = options_.provisional_steer_min;
    s.provisional_steers = min > 0 && static_cast<int>(s.touched.size()) >= min &&
                           std::none_of(s.touched.begin(), s.touched.end(), [](const TouchedLandmark& t) { return t.was_confirmed; });
  }

  // The loop's drift where measurement k was paired through an alias (core/engine/loop_closing.h), else null.
  const Mat3* loop_drift(const Scratch& s, std::size_t k) const {
    return loops_ && LoopClosing::redirected(s.loops, k) ? &loops_->drift() : nullptr;
  }

  // Montemerlo et al. 2003, §3: the proposal N(mu, Sigma) folds each paired measurement into the prediction
  // (mean p.pose, covariance p.pose_covariance: every control since the last draw) by an EKF step on the
  // pose; the pose is drawn from it. Returns the log importance weight, the product of the measurement
  // marginals N(z; h(mu), H_x Sigma H_x^T + Q) taken in the same sequence.
  double propose_and_draw(ParticleState& p, const std::vector<Measurement>& measurements, int index, Scratch& s) const {
    double log_weight = 0.0;
    Vec3 mu = p.pose.vector();
    Mat3 Sigma = p.pose_covariance;
    for (std::size_t k = 0; k < measurements.size(); ++k) {
      if (s.touched_of[k] < 0) continue;
      const TouchedLandmark& t = s.touched[s.touched_of[k]];
      if (!steers_pose(t, s)) {
        log_weight += log_likelihood_unpaired_;
        continue;
      }
      const Landmark& lm = t.landmark;
      Mat2 H_m;
      Mat23 H_x;
      const Vec2 z_hat = range_bearing_predict(Pose2::from_vector(mu), lm.mean, &H_m, &H_x);
      const Mat2 landmark_part = H_m * lm.cov * H_m.transpose();
      const Vec2 nu = range_bearing_innovation(measurements[k].z(), z_hat);
      double scale = 1.0;
      const Mat3* drift = loop_drift(s, k);
      const Mat3 pose_part = drift ? Mat3(Sigma + *drift) : Sigma;
      log_weight += likelihood_(nu, H_x * pose_part * H_x.transpose() + landmark_part + R_, &scale);
      const Mat2 Q = landmark_part + scale * R_;
      const Mat2 S = H_x * Sigma * H_x.transpose() + Q;
      const Mat32 K = Sigma * H_x.transpose() * S.inverse();
      mu += K * nu;
      mu.z() = wrap_angle(mu.z());
      const Mat3 I_KH = Mat3::Identity() - K * H_x;
      Sigma = I_KH * Sigma * I_KH.transpose() + K * Q * K.transpose();  // Joseph form keeps it SPD
    }
    p.pose = Pose2::from_vector(mu);
    p.pose_covariance = Sigma;
    draw_pose(p, index, RandomPurpose::kProposal);
    return log_weight;
  }

  // FastSlamOptions::pose_from_confirmed: a pairing with a landmark that was provisional before this scan
  // counts, for the pose and the weight, as an unpaired measurement, unless the scan pairs enough of them
  // (FastSlamOptions::provisional_steer_min).
  bool steers_pose(const TouchedLandmark& t, const Scratch& s) const {
    return !pose_from_confirmed_ || t.was_confirmed || s.provisional_steers;
  }

  // Landmark EKF updates at the drawn pose (Montemerlo 2002, eq. 8-11; Joseph form). With weight (FastSLAM
  // 1.0) returns the log importance weight, the product of the measurement likelihoods.
  double update_landmarks(const ParticleState& p, const std::vector<Measurement>& measurements, Scratch& s, bool weight) const {
    double log_weight = 0.0;
    for (std::size_t k = 0; k < measurements.size(); ++k) {
      if (s.touched_of[k] < 0) continue;
      TouchedLandmark& t = s.touched[s.touched_of[k]];
      Landmark& lm = t.landmark;
      const double ll = ekf_.update(p.pose, measurements[k].z(), lm.id, &lm.mean, &lm.cov, loop_drift(s, k));
      if (weight) log_weight += steers_pose(t, s) ? ll : log_likelihood_unpaired_;
      existence_.seen(&lm, scan_index_);
      const float sig = measurements[k].signature;
      if (!std::isnan(sig)) lm.signature = std::isnan(lm.signature) ? sig : lm.signature + 0.2f * (sig - lm.signature);
    }
    return log_weight;
  }

  // New landmarks from the measurements the association left unexplained (inverse measurement model); a
  // new or spurious measurement is weighted by the likelihood at the new-landmark gate.
  double add_new_landmarks(ParticleState& p, const std::vector<Measurement>& measurements, Scratch& s) const {
    double log_weight = 0.0;
    for (std::size_t k = 0; k < measurements.size(); ++k) {
      if (s.decision[k] == kSpurious) log_weight += log_likelihood_unpaired_;
      if (s.decision[k] != kNewLandmark) continue;
      log_weight += log_likelihood_unpaired_;
      Landmark lm;
      ARBOR_CHECK(p.next_id < std::numeric_limits<LandmarkId>::max(), "landmark ids are exhausted");
      lm.id = p.next_id++;
      ekf_.start(p.pose, measurements[k].z(), &lm.mean, &lm.cov);
      existence_.start(&lm, scan_index_);
      lm.signature = measurements[k].signature;
      lm.truth_label = measurements[k].truth_id >= 0 ? measurements[k].truth_id : -1;
      s.touched_of[k] = static_cast<int>(s.touched.size());
      s.touched.push_back({lm, true});
    }
    return log_weight;
  }

  const SetSpread* spread() const { return set_spread_ ? &*set_spread_ : nullptr; }  // gate_covariance = set

  // One decision per measurement: landmark id, kNewLandmark or kSpurious.
  void decide(ParticleState& p, const ScenarioStep& step, Scratch& s) {
    strategy_.solve(s.problem.problem, s.strategy, s.result);
    ARBOR_CHECK(s.result.pairing.size() == step.measurements.size(), "strategy {} returned {} decisions for {} measurements",
                Assoc::kName, s.result.pairing.size(), step.measurements.size());
    s.decision = s.result.pairing;
    p.step_search = s.result.stats;
    p.rejected += s.result.stats.rejected;
  }

  // Existence evidence against the landmarks the scan should have seen and did not (core/engine/existence.h);
  // s.nearby must hold the landmarks gathered this scan. Loop closing's bookkeeping runs only when it is on.
  void apply_negative_evidence(ParticleState& p, Scratch& s, std::span<const TouchedLandmark> touched) {
    existence_.miss_unseen(s.nearby, touched, p.pose, scan_index_, scan_.view(), loops_ ? &s.loops : nullptr, &p.map, &s.erased);
    s.nearby.clear();
    if (loops_) {
      s.loops.redirected.clear();
      s.loops.retired.clear();
      LoopClosing::drop_aliases_of(&p.aliases, s.erased);
    }
  }

  // Relocalisation (core/engine/relocalization.h), between steps: a re-seeding starts the weights equal.
  void relocalize_if_lost(const ScenarioStep& step) {
    const auto begin = [&](AssociationProblem* problem) { scan_.begin(Mat3::Zero(), problem); };
    const auto candidate = [&](const Landmark& lm, const Pose2& pose) { return scan_.candidate(lm, pose, spread()); };
    const auto in_view = [&](const Vec2& z) { return scan_.view().in_evidence_view(z); };
    if (!relocalization_->relocalize_if_lost(particles_, best_particle(), step, step_index_, scan_index_, begin, candidate, in_view))
      return;
    weights_.assign(particles_.size(), 1.0 / particles_.size());
    last_n_eff_ = static_cast<double>(particles_.size());
    stats_.relocalized = true;
  }

  FastSlamOptions options_;
  MotionModel motion_;
  Mat2 R_;                           // the measurement noise
  ScanProblem<Assoc::kTraits.uses_ground_truth> scan_;
  MeasurementLikelihood likelihood_;
  LandmarkEkf ekf_;
  ExistenceEvidence existence_;
  Assoc strategy_;
  double log_likelihood_unpaired_ = 0.0;
  double weight_exponent_ = 1.0;     // FastSlamOptions::effective_weight_exponent
  double last_time_s_ = 0.0;
  BodyProcessNoise step_noise_;      // the step's control noise in the start frame, shared by every particle
  ComposedMotion pending_motion_;    // the controls of the deferred steps since the last one that predicted
  bool pose_from_confirmed_ = false;
  bool keep_localities_ = true;
  tbb::task_arena arena_;
  std::vector<ParticleState> particles_;
  std::vector<double> weights_;
  tbb::enumerable_thread_specific<Scratch> scratch_;
  // The policies beside the paper's steps, each held only when its option is on.
  std::optional<Relocalization> relocalization_;  // FastSlamOptions::relocalize
  std::optional<LoopClosing> loops_;              // FastSlamOptions::close_loops (not with known association)
  std::optional<SetSpread> set_spread_;           // FastSlamOptions::gate_covariance = set
  std::optional<ResampleMove> moves_;             // FastSlamOptions::move_window > 0
  std::optional<Mat3> roughening_kernel_;  // FastSlamOptions::roughen: added at the step after a resampling
  std::int64_t step_index_ = 0;
  std::int32_t scan_index_ = 0;  // scans before this step: a landmark's born_scan
  double last_n_eff_ = 0.0;
  StepStats stats_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_FASTSLAM_H_
