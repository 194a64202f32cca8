// Relocalisation (FastSlamOptions::relocalize), a policy beside the engine: a kidnapped robot (or one whose
// drift defeats the gates at a loop closure) is found again by a pose-free search of the best particle's map,
// and every particle is re-seeded there. It runs between steps, once per scan, plus one per-particle count;
// the engine holds it only when the option is on, so off it costs nothing.
#ifndef ARBOR_CORE_ENGINE_RELOCALIZATION_H_
#define ARBOR_CORE_ENGINE_RELOCALIZATION_H_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "core/association/association_problem.h"
#include "core/check.h"
#include "core/engine/loop_closing.h"
#include "core/engine/touched_landmark.h"
#include "core/math/angles.h"
#include "core/math/pose2.h"
#include "core/models/range_bearing_model.h"
#include "core/types/scenario.h"
#include "core/types/step_decisions.h"

namespace arbor {

// A pose-free search of a map for one scan (the locality tree, from variants/): fills the pose world_T_robot
// that its answer implies and returns how many measurements it pairs (0 without a verified pose). The
// problem's candidates are the map's landmarks, ascending id, with their world positions and localities.
using Relocalizer = std::function<int(const AssociationProblem& problem, Pose2* world_T_robot)>;

// When to search and which found pose to trust. A kidnapped robot (or one whose drift defeats the gates at a
// loop closure) pairs little of what it sees with the map it had: its particles predict landmarks where none
// are. The best particle's settled map (landmarks started kSettledScans scans ago or more) is then searched
// without a prior for this scan. The newer landmarks are left out: after a kidnap they are copies of what the
// robot sees, placed at the wrong pose, which the particle pairs from the next scan on and which would
// confirm the wrong pose. A found pose re-seeds the particles only if it is elsewhere, pairs more
// measurements than the particle paired with settled landmarks (by kMargin), pairs a third of the settled
// landmarks it predicts in view (explains_enough_in_view), has more evidence than the particle's pose once the
// landmarks each predicts and misses count against it (scan_evidence), and the next scan finds the same
// correction (a coincidence in the map rarely repeats after the odometry's motion; scans too small to search
// in between neither confirm nor refute it, for up to kConfirmScans scans). Every particle then takes the
// best particle's map, the pose, and a covariance of kSigma; the weights start equal.
class Relocalization {
 public:
  Relocalization(Relocalizer relocalizer, int min_pairings) : relocalizer_(std::move(relocalizer)), min_pairings_(min_pairings) {}

  // Between steps, before a scan's particles run: no particle has paired anything yet.
  void begin_scan(int particles) { paired_settled_.assign(particles, 0); }

  // The per-particle hook, after association: counts particle index's pairings with settled landmarks
  // (touched_of: per measurement, its landmark's index in touched or -1). Particles write their own entry.
  void count_pairings(int index, std::span<const TouchedLandmark> touched, std::span<const int> touched_of,
                      std::int32_t scan_index) {
    int paired = 0;
    for (int t : touched_of) paired += t >= 0 && settled(touched[t].landmark, scan_index);
    paired_settled_[index] = paired;
  }

  // Between steps, after weighting: when this scan confirms a relocalised pose for particle best, every
  // particle takes that particle's map (less what it started while lost), the pose and a covariance of kSigma,
  // with log-weight 0; returns whether it re-seeded them. begin_problem(&problem) fills the scan's
  // measurements, no candidates, P = 0; candidate(lm, pose) is landmark lm as an association candidate seen
  // from pose, and in_view(z) whether a landmark predicted at z lies well inside the sensor's view.
  template <class P, class BeginProblem, class Candidate, class InView>
  bool relocalize_if_lost(std::vector<P>& particles, int best, const ScenarioStep& step, std::int64_t step_index,
                          std::int32_t scan_index, const BeginProblem& begin_problem, const Candidate& candidate,
                          const InView& in_view) {
    const std::optional<Pose2> found = search(static_cast<int>(step.measurements.size()), best, particles[best], scan_index,
                                              begin_problem, candidate, in_view);
    if (!found) return false;
    P source = particles[best];
    // This scan's pose was recorded before the search; the trajectory should show where the scan was taken.
    source.history.replace_newest({step.time_s, *found});
    forget_landmarks_started_lost(source, step_index, scan_index);
    const Mat3 covariance = kSigma.cwiseAbs2().asDiagonal();
    for (auto& p : particles) {
      p = source;
      p.pose = *found;
      p.pose_covariance = covariance;
      p.log_weight = 0.0;
    }
    ++relocalizations_;
    return true;
  }

  // Scans at which every particle was re-seeded at a relocalised pose.
  std::int64_t relocalizations() const { return relocalizations_; }

 private:
  // Whether this scan confirms a relocalised pose for particle best (of index best_index), and where.
  template <class P, class BeginProblem, class Candidate, class InView>
  std::optional<Pose2> search(int measurements, int best_index, const P& best, std::int32_t scan_index,
                              const BeginProblem& begin_problem, const Candidate& candidate, const InView& in_view) {
    const int m = measurements;
    const int paired_settled = paired_settled_[best_index];
    if (m < min_pairings_) {
      // Too few measurements to search: no evidence either way, so a pending correction waits for the next
      // scan that can confirm it (a kidnapped robot in a sparse corridor lost its found pose to one scan of
      // 4 measurements between two that found it).
      if (pending_correction_ && scan_index - pending_scan_ > kConfirmScans) pending_correction_.reset();
      return std::nullopt;
    }
    const bool lost = 2 * paired_settled < m;
    if (lost && !lost_since_scan_) lost_since_scan_ = scan_index;
    else if (!lost && !pending_correction_) lost_since_scan_.reset();
    if (!pending_correction_ && !lost) return std::nullopt;
    AssociationProblem& problem = problem_;
    begin_problem(&problem);
    int in_view_here = 0;  // settled landmarks the particle's own pose predicts well inside the view
    best.map.for_each([&](const Landmark& lm) {
      if (!lm.confirmed || !settled(lm, scan_index)) return;
      problem.candidates.push_back(candidate(lm, best.pose));
      in_view_here += in_view(problem.candidates.back().z_hat);
    });
    Pose2 found;
    const int pairings = problem.candidates.size() < 2 ? 0 : relocalizer_(problem, &found);
    const auto near = [](const Pose2& a, const Pose2& b) {
      return (a.position() - b.position()).norm() <= kAgreementM && std::abs(wrap_angle(a.theta - b.theta)) <= kAgreementRad;
    };
    const auto refused = [&] {
      if (pairings < min_pairings_ || pairings < paired_settled + kMargin || near(found, best.pose)) return true;
      int in_view_found = 0;
      best.map.for_each([&](const Landmark& lm) {
        if (lm.confirmed && settled(lm, scan_index)) in_view_found += in_view(range_bearing_predict(found, lm.mean));
      });
      return !explains_enough_in_view(pairings, in_view_found) ||
             scan_evidence(pairings, in_view_found) < scan_evidence(paired_settled, in_view_here) + kMargin;
    };
    if (refused()) {
      pending_correction_.reset();
      return std::nullopt;
    }
    // The correction world -> world that carries the particle's pose onto the found one. The particle moves
    // by the odometry, as the robot does, so at the next scan the last correction, applied to the particle's
    // pose, predicts where the search should find it again.
    const Pose2 correction = found.compose(best.pose.between(Pose2{}));
    const bool confirmed = pending_correction_ && near(pending_correction_->compose(best.pose), found);
    pending_correction_ = correction;
    pending_scan_ = scan_index;
    if (!confirmed) return std::nullopt;
    pending_correction_.reset();
    return found;
  }

  // A re-seeded particle forgets the landmarks it started while lost (since the first scan of the current
  // streak of scans that paired under half with settled landmarks): its wrong pose put them where they are,
  // as copies of what the robot saw. Kept, they settle, and a later search can pair a scan with them and
  // carry the robot back into the wrong frame (clustered world 8, kidnapped: re-seeded twice more after a
  // right recovery, 2.2 m off at the end; with this, 0.03 m). The removal is recorded as this scan's
  // negative evidence, so the decisions replay to the same map. Ends the lost streak.
  template <class P>
  void forget_landmarks_started_lost(P& p, std::int64_t step_index, std::int32_t scan_index) {
    const std::int32_t since = lost_since_scan_.value_or(scan_index);
    lost_since_scan_.reset();
    StepDecisions decisions = p.decisions.newest();
    ARBOR_CHECK(decisions.step == step_index, "the re-seeded particle recorded no decisions for step {}", step_index);
    const std::size_t kept = decisions.erased.size();
    p.map.for_each([&](const Landmark& lm) {
      if (lm.born_scan >= since) decisions.erased.push_back(lm.id);
    });
    if (decisions.erased.size() == kept) return;
    const std::span<const LandmarkId> forgotten = std::span<const LandmarkId>(decisions.erased).subspan(kept);
    for (LandmarkId id : forgotten) p.map.erase(id);
    LoopClosing::drop_aliases_of(&p.aliases, forgotten);
    p.decisions.replace_newest(std::move(decisions));
  }

  static bool settled(const Landmark& lm, std::int32_t scan_index) { return scan_index - lm.born_scan >= kSettledScans; }

  // Negative evidence against a found pose: it must pair at least kMinExplainedInView of the settled
  // landmarks it predicts inside the sensor's evidence view. A coincidence in a well-mapped area pairs a few
  // and leaves most of what the map puts in view unseen; scans that see the same landmarks repeat it, so the
  // next scan's confirmation cannot catch it (uniform world 20 of the simulator before d43e3e0: 5 of 20-22,
  // twice, 70 m away; now clustered world 3).
  static bool explains_enough_in_view(int pairings, int in_view) { return pairings >= kMinExplainedInView * in_view; }

  // The scan's evidence for a pose against the settled map: one for each measurement it pairs, less one for
  // each settled landmark it predicts well inside the view that goes unpaired (a missed detection). The found
  // pose must beat the particle's own pose on these equal terms, by kMargin. Judged by its pairings
  // alone, the particle's pose looks lost wherever the robot explores ground its map does not cover: it
  // predicts nothing there, so it misses nothing. In clustered worlds without a kidnap, coincidences 37-57 m
  // away that paired 5 of 6-12 measurements re-seeded 3 of 40 runs (ATE up to 0.58 -> 15.6 m) while the
  // particle paired 1-2 settled landmarks of the 0-3 it predicted (evidence 0-1 against the found pose's -5
  // to 1). A kidnapped robot's believed pose misses what it predicts. With this check, recovery within 10
  // scans of a kidnap is unchanged over 40 seeds of uniform, rooms and clustered worlds, and none of the runs
  // without a kidnap is re-seeded away from the truth (results/association/d43e3e0_vm_gcc-12.2.0).
  static int scan_evidence(int pairings, int in_view) { return pairings - std::max(0, in_view - pairings); }

  static constexpr int kSettledScans = 10;
  static constexpr int kMargin = 3;
  // A third: in 419 found poses that were right (kidnap study, seeds 1-20, uniform and rooms) the least was
  // 0.38, in rooms, where walls hide landmarks the map predicts in view; the wrong ones paired 0.23-0.36 (the
  // 0.36 one, in rooms, was not confirmed by the next scan).
  static constexpr double kMinExplainedInView = 1.0 / 3.0;
  static constexpr int kConfirmScans = 5;  // the most scans between a found pose and its confirmation
  static constexpr double kAgreementM = 1.0;
  static constexpr double kAgreementRad = 0.1;
  inline static const Vec3 kSigma{0.2, 0.2, 0.03};  // [m, m, rad]: a fitted pose from ~5 pairings

  Relocalizer relocalizer_;
  int min_pairings_;
  AssociationProblem problem_;
  std::vector<int> paired_settled_;          // per particle: this scan's pairings with settled landmarks
  std::optional<Pose2> pending_correction_;  // the last scan's unconfirmed relocalisation, as a correction
  std::int32_t pending_scan_ = 0;            // the scan that found it
  std::optional<std::int32_t> lost_since_scan_;  // the first scan of the best particle's current lost streak
  std::int64_t relocalizations_ = 0;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RELOCALIZATION_H_
