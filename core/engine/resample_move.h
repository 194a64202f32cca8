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

#include <memory>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/types/landmark.h"

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

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RESAMPLE_MOVE_H_
