// Resample-move (Gilks & Berzuini 2001, "Following a moving target", JRSS B 63): after a resampling, the copies
// of one parent share their whole recent path, and no later step can revise it. A Metropolis-Hastings move over
// the poses of a particle's last scans, its pairings held fixed, lets each copy revise that path (above all the
// heading a stretch without landmarks left) under the exact target
//   p(x_s..x_t | x_{s-1}, u, z, m_{s-1})  ∝  prod_k p(x_k | x_{k-1}, u_k) p(z_k | x_k, m_{k-1}),
// where p(z_k | x_k, m_{k-1}) is the product of the landmark EKFs' marginals N(z; h(x, mu), H P H^T + R) taken in
// the scan's order. The landmark states before the window are kept per scan, so the move recomputes those
// marginals (and the landmarks the window touched) by replaying the window's EKF updates along the proposed
// path. A move leaves the target invariant, so the particle weights stay equal. The proposal perturbs one
// scan's motion residual (relative to its predicted motion, in the previous pose's frame) and carries the later
// poses along rigidly, so only that scan's motion density changes; the scan is drawn with probability half
// uniform and half by its prediction's heading variance, so a long gap is revised most often.
#ifndef ARBOR_CORE_ENGINE_RESAMPLE_MOVE_H_
#define ARBOR_CORE_ENGINE_RESAMPLE_MOVE_H_

#include <cmath>
#include <cstdint>
#include <memory>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "core/engine/fastslam_options.h"
#include "core/engine/landmark_ekf.h"
#include "core/engine/rng.h"
#include "core/engine/touched_landmark.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/types/landmark.h"
#include "core/types/scenario.h"

namespace arbor {

// One measurement a scan paired with a landmark or started one from, in the order the scan applied them.
struct MovePairing {
  Vec2 z;
  LandmarkId id = kNoLandmark;
  bool is_new = false;
};

// A landmark's estimate before a scan updated it.
struct LandmarkEstimate {
  LandmarkId id = kNoLandmark;
  Vec2 mean = Vec2::Zero();
  Mat2 cov = Mat2::Zero();
};

// One scan in the window: its pose draw, the motion prediction that led to it and what it did to the map.
struct MoveScan {
  Pose2 pose;                              // the draw at this scan
  Pose2 predicted;                         // the prediction's mean, in the previous draw's frame
  Mat3 predicted_cov = Mat3::Zero();       // and its covariance, in the same frame
  std::vector<MovePairing> pairings;
  std::vector<LandmarkEstimate> before;    // the existing landmarks it paired, as they were before it
  int history_entries_before = 0;          // pose-history entries recorded after the previous draw, before this
};

// A particle's last scans, oldest first, shared between the copies of a resampling until one moves.
struct MoveWindow {
  Pose2 anchor;                                     // the draw before the window's first scan: held fixed
  std::vector<std::shared_ptr<const MoveScan>> scans;
  int history_entries_since_draw = 0;               // recorded after the newest draw
  Pose2 pending_predicted;                          // the current scan's prediction, until it is drawn
  Mat3 pending_cov = Mat3::Zero();

  const Pose2& last_draw() const { return scans.empty() ? anchor : scans.back()->pose; }

  // Appends a drawn scan; the oldest one leaves the window when it is full, its pose the new anchor.
  void push(std::shared_ptr<const MoveScan> scan, int window) {
    scans.push_back(std::move(scan));
    if (static_cast<int>(scans.size()) > window) {
      anchor = scans.front()->pose;
      scans.erase(scans.begin());
    }
    history_entries_since_draw = 0;
  }
};

// The landmarks a scan is about to update, as they are before it (MoveScan::before).
inline std::vector<LandmarkEstimate> estimates_before(std::span<const TouchedLandmark> touched) {
  std::vector<LandmarkEstimate> before;
  for (const TouchedLandmark& t : touched) before.push_back({t.landmark.id, t.landmark.mean, t.landmark.cov});
  return before;
}

// The scan just drawn at pose, for window w: its prediction, its draw, and its pairings in the order the
// engine applied them, updates of existing landmarks before new ones (touched_of: per measurement, its index
// in touched or -1). Without measurements (an empty scan) it pairs nothing.
inline std::shared_ptr<const MoveScan> drawn_scan(const MoveWindow& w, const Pose2& pose, std::vector<LandmarkEstimate> before,
                                                  std::span<const TouchedLandmark> touched, std::span<const int> touched_of,
                                                  const std::vector<Measurement>* measurements) {
  auto scan = std::make_shared<MoveScan>();
  scan->pose = pose;
  scan->predicted = w.pending_predicted;
  scan->predicted_cov = w.pending_cov;
  scan->before = std::move(before);
  scan->history_entries_before = w.history_entries_since_draw;
  if (measurements)
    for (bool fresh : {false, true})
      for (std::size_t k = 0; k < measurements->size(); ++k) {
        if (touched_of[k] < 0 || touched[touched_of[k]].is_new != fresh) continue;
        scan->pairings.push_back({(*measurements)[k].z(), touched[touched_of[k]].landmark.id, fresh});
      }
  return scan;
}

// The prediction's covariance in the frame of the pose it started from (x, y rotated by -heading).
inline Mat3 in_frame_of(const Pose2& from, const Mat3& world_cov) {
  Mat3 R = Mat3::Identity();
  const double c = std::cos(from.theta), s = std::sin(from.theta);
  R.topLeftCorner<2, 2>() << c, s, -s, c;
  return R * world_cov * R.transpose();
}

// The residual of the motion from `from` to `to` against the prediction (relative pose minus predicted, heading
// wrapped) and its Gaussian log-density up to a constant.
inline Vec3 motion_residual(const Pose2& from, const Pose2& to, const MoveScan& scan) {
  const Pose2 r = from.between(to);
  return {r.x - scan.predicted.x, r.y - scan.predicted.y, wrap_angle(r.theta - scan.predicted.theta)};
}
inline double motion_log_density(const Vec3& residual, const Mat3& cov) {
  const Mat3 regular = cov + 1e-12 * Mat3::Identity();  // a still robot predicts no spread at all
  return -0.5 * residual.dot(regular.ldlt().solve(residual));
}

// The window's log target along `poses` (one per scan): motion densities plus the replayed measurement
// marginals. update(pose, z, &estimate) applies one landmark EKF update and returns its log-likelihood;
// start(pose, z, &estimate) initialises a new landmark. Fills `after` (every landmark the window touched, as
// the replay leaves it) and `before` (per scan, the estimates before it, as MoveScan::before orders them).
template <class Update, class Start>
double window_log_target(const MoveWindow& w, const std::vector<Pose2>& poses, const Update& update, const Start& start,
                         std::vector<LandmarkEstimate>* after, std::vector<std::vector<LandmarkEstimate>>* before) {
  double log_target = 0.0;
  after->clear();
  before->resize(w.scans.size());
  const auto state_of = [&](LandmarkId id) -> LandmarkEstimate* {
    for (auto& e : *after)
      if (e.id == id) return &e;
    return nullptr;
  };
  for (std::size_t k = 0; k < w.scans.size(); ++k) {
    const MoveScan& scan = *w.scans[k];
    const Pose2& from = k == 0 ? w.anchor : poses[k - 1];
    log_target += motion_log_density(motion_residual(from, poses[k], scan), scan.predicted_cov);
    auto& out = (*before)[k];
    out.clear();
    for (const LandmarkEstimate& b : scan.before) {
      if (!state_of(b.id)) after->push_back(b);  // first touched in the window: its state before the window
      out.push_back(*state_of(b.id));
    }
    for (const MovePairing& m : scan.pairings) {
      if (m.is_new) {
        LandmarkEstimate e{m.id};
        start(poses[k], m.z, &e);
        after->push_back(e);
      } else {
        log_target += update(poses[k], m.z, state_of(m.id));
      }
    }
  }
  return log_target;
}

// The proposal: scan k's relative motion moves by scale * sqrt(predicted_cov) * noise (symmetric), the later
// scans keep their relative motions. noise: three standard normal deviates.
inline std::vector<Pose2> propose_path(const MoveWindow& w, const std::vector<Pose2>& poses, std::size_t k, double scale,
                                       const Vec3& noise) {
  std::vector<Pose2> out = poses;
  const Pose2& from = k == 0 ? w.anchor : poses[k - 1];
  Eigen::SelfAdjointEigenSolver<Mat3> eig(w.scans[k]->predicted_cov);
  const Vec3 step = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().cwiseProduct(scale * noise);
  const Pose2 r = from.between(poses[k]);
  out[k] = from.compose(Pose2::from_vector(r.vector() + step));
  for (std::size_t j = k + 1; j < poses.size(); ++j) out[j] = out[j - 1].compose(poses[j - 1].between(poses[j]));
  return out;
}

// Which scan a proposal perturbs, for a uniform deviate u: half uniformly, half in proportion to the heading
// variance of the scan's prediction. A fixed distribution, so the proposal stays symmetric.
inline std::size_t pick_scan(const MoveWindow& w, double u) {
  const std::size_t n = w.scans.size();
  double total = 0.0;
  for (const auto& s : w.scans) total += std::max(s->predicted_cov(2, 2), 0.0);
  double acc = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const double share = total > 0.0 ? std::max(w.scans[k]->predicted_cov(2, 2), 0.0) / total : 1.0 / n;
    acc += 0.5 / n + 0.5 * share;
    if (u < acc) return k;
  }
  return n - 1;
}

// Writes an accepted path into particle p (the engine's Particle: move, history, pose, pose_covariance, map):
// the window's scans, the landmarks it touched (where the map still holds them), the pose history since the
// anchor and the prediction since the newest draw, carried along rigidly.
template <class Particle>
void apply_move(Particle& p, const std::vector<Pose2>& poses, const std::vector<LandmarkEstimate>& after,
                const std::vector<std::vector<LandmarkEstimate>>& before) {
  MoveWindow& w = p.move;
  const std::size_t n = w.scans.size();
  std::vector<Pose2> old(n);
  for (std::size_t k = 0; k < n; ++k) old[k] = w.scans[k]->pose;
  // The history, newest first: entries after draw k are carried with it; draw k's own entry becomes poses[k].
  std::size_t count = w.history_entries_since_draw;
  for (std::size_t k = n; k-- > 1;) count += 1 + w.scans[k]->history_entries_before;
  count += 1;
  auto entries = p.history.newest_entries(count);
  std::size_t e = 0;
  const auto carry = [&](std::size_t k, int how_many) {
    for (int j = 0; j < how_many; ++j, ++e) entries[e].pose = poses[k].compose(old[k].between(entries[e].pose));
  };
  carry(n - 1, w.history_entries_since_draw);
  for (std::size_t k = n; k-- > 0;) {
    entries[e++].pose = poses[k];
    if (k > 0) carry(k - 1, w.scans[k]->history_entries_before);
  }
  p.history.drop_newest(count);
  for (std::size_t j = count; j-- > 0;) p.history.push(entries[j]);
  // The prediction since the newest draw, and its covariance turned with it.
  p.pose = poses[n - 1].compose(old[n - 1].between(p.pose));
  const Mat3 turn = in_frame_of(Pose2{0.0, 0.0, old[n - 1].theta - poses[n - 1].theta}, Mat3::Identity());
  p.pose_covariance = turn * p.pose_covariance * turn.transpose();
  for (std::size_t k = 0; k < n; ++k) {
    auto scan = std::make_shared<MoveScan>(*w.scans[k]);
    scan->pose = poses[k];
    scan->before = before[k];
    w.scans[k] = std::move(scan);
  }
  for (const LandmarkEstimate& est : after) {
    const Landmark* lm = p.map.find(est.id);
    if (!lm) continue;  // removed since by negative evidence
    Landmark moved = *lm;
    moved.mean = est.mean;
    moved.cov = est.cov;
    p.map.set(moved);
  }
}

// One particle's moves after a resampling: `steps` proposals at scales scale, scale / 2, ..., each accepted
// with probability min(1, target ratio). log_target(window, poses, &after, &before) is window_log_target with
// the engine's landmark update. Returns the number accepted; the particle changes only if one was.
template <class Particle, class LogTarget>
int move_particle(Particle& p, const LogTarget& log_target, int steps, double scale, RandomStream& rng) {
  const MoveWindow& w = p.move;
  if (w.scans.empty()) return 0;
  std::vector<Pose2> poses;
  for (const auto& scan : w.scans) poses.push_back(scan->pose);
  std::vector<LandmarkEstimate> after, after_proposed;
  std::vector<std::vector<LandmarkEstimate>> before, before_proposed;
  double current = log_target(w, poses, &after, &before);
  int accepted = 0;
  for (int step = 0; step < steps; ++step, scale *= 0.5) {
    const std::size_t k = pick_scan(w, rng.uniform());
    const Vec3 noise = draw_vec3([&] { return rng.normal(); });
    const double u = rng.uniform();
    std::vector<Pose2> proposed = propose_path(w, poses, k, scale, noise);
    const double proposed_target = log_target(w, proposed, &after_proposed, &before_proposed);
    if (!(std::log(u) < proposed_target - current)) continue;
    poses.swap(proposed);
    after.swap(after_proposed);
    before.swap(before_proposed);
    current = proposed_target;
    ++accepted;
  }
  if (accepted > 0) apply_move(p, poses, after, before);
  return accepted;
}

// The policy the engine holds when FastSlamOptions::move_window > 0: it keeps each particle's window at every
// scan, and after a resampling moves every particle.
class ResampleMove {
 public:
  // weight_exponent: the engine's (FastSlamOptions::effective_weight_exponent).
  ResampleMove(const FastSlamOptions& options, double weight_exponent, const LandmarkEkf& ekf)
      : window_(options.move_window), steps_(options.move_steps), scale_(options.move_scale), seed_(options.seed),
        weight_exponent_(weight_exponent), ekf_(ekf) {}

  // At a scan, before the draw: the prediction since the window's last draw, in that draw's frame.
  static void predicted(const Pose2& pose, const Mat3& pose_covariance, MoveWindow* w) {
    w->pending_predicted = w->last_draw().between(pose);
    w->pending_cov = in_frame_of(w->last_draw(), pose_covariance);
  }

  // The scan just drawn joins the window (drawn_scan gives its arguments).
  void record(std::shared_ptr<const MoveScan> scan, MoveWindow* w) const { w->push(std::move(scan), window_); }

  // The window's log target along poses, replaying its landmark updates as the engine made them.
  double log_target(const MoveWindow& w, const std::vector<Pose2>& poses, std::vector<LandmarkEstimate>* after,
                    std::vector<std::vector<LandmarkEstimate>>* before) const {
    const auto update = [&](const Pose2& pose, const Vec2& z, LandmarkEstimate* e) {
      // The tempered likelihood the weights use (FastSlamOptions::weight_exponent): the moves target the same
      // posterior the set stands for.
      return e ? weight_exponent_ * ekf_.update(pose, z, e->id, &e->mean, &e->cov) : 0.0;
    };
    const auto start = [&](const Pose2& pose, const Vec2& z, LandmarkEstimate* e) { ekf_.start(pose, z, &e->mean, &e->cov); };
    return window_log_target(w, poses, update, start, after, before);
  }

  // The landmarks window w touched, replayed along the path it holds.
  std::vector<LandmarkEstimate> replay(const MoveWindow& w) const {
    std::vector<Pose2> poses;
    for (const auto& scan : w.scans) poses.push_back(scan->pose);
    std::vector<LandmarkEstimate> after;
    std::vector<std::vector<LandmarkEstimate>> before;
    log_target(w, poses, &after, &before);
    return after;
  }

  // After a resampling at step: every particle tries move_steps proposals over its window, at scales
  // move_scale, move_scale / 2, move_scale / 4, ... in turn, each with its own stream (seed, step, particle,
  // kMove), in parallel. Adds the proposals and acceptances to *proposed and *accepted.
  template <class Particle>
  void move_all(std::vector<Particle>& particles, std::int64_t step, tbb::task_arena& arena, std::int64_t* proposed,
                std::int64_t* accepted) const {
    std::vector<int> accepted_by(particles.size(), 0);
    const auto target = [&](const MoveWindow& w, const std::vector<Pose2>& poses, std::vector<LandmarkEstimate>* after,
                            std::vector<std::vector<LandmarkEstimate>>* before) { return log_target(w, poses, after, before); };
    arena.execute([&] {
      tbb::parallel_for(0, static_cast<int>(particles.size()), [&](int i) {
        RandomStream rng(seed_, step, i, RandomPurpose::kMove);
        accepted_by[i] = move_particle(particles[i], target, steps_, scale_, rng);
      });
    });
    for (std::size_t i = 0; i < particles.size(); ++i) {
      *accepted += accepted_by[i];
      *proposed += particles[i].move.scans.empty() ? 0 : steps_;
    }
  }

 private:
  int window_;
  int steps_;
  double scale_;
  std::uint64_t seed_;
  double weight_exponent_;
  LandmarkEkf ekf_;
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RESAMPLE_MOVE_H_
