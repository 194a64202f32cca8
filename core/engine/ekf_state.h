// EKF-SLAM's state: one Gaussian over the pose and every landmark, with the full joint covariance
// (Smith, Self & Cheeseman 1990; Probabilistic Robotics Table 10.1). Landmarks sit in ascending id order, two
// rows each after the pose's three, so slot i is the i-th smallest id. The operations keep the covariance's
// cost where the method puts it: a control touches only the pose's 3x3 block, and the pose-landmark cross
// terms it transforms (G_x P_xm) are settled once at the next scan, so the 61,660 odometry steps between
// Victoria Park's scans cost O(1) each; an update is O(n^2) in the state size n, as EKF-SLAM's always is.
#ifndef ARBOR_CORE_ENGINE_EKF_STATE_H_
#define ARBOR_CORE_ENGINE_EKF_STATE_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "core/check.h"
#include "core/engine/numerical_breakdown.h"
#include "core/math/angles.h"
#include "core/math/covariance_floor.h"
#include "core/math/eigen_types.h"
#include "core/math/pose2.h"
#include "core/models/motion_model.h"
#include "core/models/range_bearing_model.h"
#include "core/types/landmark.h"

namespace arbor {

// The 2 x n rows H P of one measurement: its prediction's covariance with every state variable.
using MeasurementCross = Eigen::Matrix<double, 2, Eigen::Dynamic>;

// One paired measurement of an update: its innovation z - h(x, m) and its rows H P at the current mean, as
// measurement_cross gave them for the association (computed once per candidate, not again for the update).
struct EkfObservation {
  Vec2 innovation;
  const MeasurementCross* cross = nullptr;
};

class EkfState {
 public:
  EkfState(const Pose2& pose, const Mat3& covariance) {
    reserve(3);
    mean_.head<3>() = pose.vector();
    cov_.topLeftCorner<3, 3>() = covariance;
  }

  int landmarks() const { return static_cast<int>(ids_.size()); }
  int dimension() const { return 3 + 2 * landmarks(); }
  Pose2 pose() const { return Pose2::from_vector(mean_.head<3>()); }
  Mat3 pose_covariance() const { return cov_.topLeftCorner<3, 3>(); }
  LandmarkId id(int slot) const { return ids_[slot]; }
  Vec2 landmark_mean(int slot) const { return mean_.segment<2>(row(slot)); }
  Mat2 landmark_covariance(int slot) const { return cov_.block<2, 2>(row(slot), row(slot)); }
  // The slot holding id, or -1.
  int slot_of(LandmarkId id) const {
    const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
    return it != ids_.end() && *it == id ? static_cast<int>(it - ids_.begin()) : -1;
  }
  // The joint covariance, n x n (settle() first for the pose-landmark blocks).
  auto covariance() const { return cov_.topLeftCorner(dimension(), dimension()); }
  std::size_t bytes() const { return sizeof(double) * (cov_.size() + mean_.size()) + sizeof(LandmarkId) * ids_.capacity(); }

  // The EKF prediction through one control (Probabilistic Robotics Table 10.1, lines 3-5): x <- g(x, u),
  // P_xx <- G P_xx G^T + Q. The cross terms P_xm <- G P_xm wait in the accumulated G until settle().
  void predict(const MotionModel& motion, const Vec3& u, const BodyProcessNoise& noise) {
    Pose2 x = pose();
    const Mat3 Q = noise.at(x.theta);
    Mat3 G = Mat3::Identity();
    x = motion.apply(x, u, &G);
    mean_.head<3>() = x.vector();
    cov_.topLeftCorner<3, 3>() = G * cov_.topLeftCorner<3, 3>() * G.transpose() + Q;
    pending_G_ = G * pending_G_;
  }

  // Applies the controls' accumulated Jacobian to the pose-landmark cross covariance.
  void settle() {
    if (pending_G_ == Mat3::Identity()) return;
    const int m = 2 * landmarks();
    if (m > 0) {
      const Eigen::MatrixXd cross = pending_G_ * cov_.block(0, 3, 3, m);
      cov_.block(0, 3, 3, m) = cross;
      cov_.block(3, 0, m, 3) = cross.transpose();
    }
    pending_G_.setIdentity();
  }

  // The 2 x n block H P of a measurement of slot with Jacobians H_pose and H_landmark: its covariance with
  // every state variable. Two of them give the innovations' covariance, C_ab = (H P)_a H_b^T.
  MeasurementCross measurement_cross(int slot, const Mat23& H_pose, const Mat2& H_landmark) const {
    require_settled();
    const int n = dimension();
    return H_pose * cov_.topLeftCorner(3, n) + H_landmark * cov_.block(row(slot), 0, 2, n);
  }
  Mat2 innovation_block(const MeasurementCross& HP_a, int slot_b, const Mat23& H_pose_b,
                        const Mat2& H_landmark_b) const {
    return HP_a.leftCols<3>() * H_pose_b.transpose() + HP_a.middleCols<2>(row(slot_b)) * H_landmark_b.transpose();
  }

  // One batch update with every paired measurement of a scan (Table 10.1, lines 12-18, stacked):
  // K = P H^T S^-1, x <- x + K nu, P <- P - P H^T S^-1 H P. S, the stacked innovations' covariance, is given:
  // the association tested with the same matrix. The covariance is updated as P - V V^T with V = P H^T L^-T
  // (S = L L^T), symmetric by construction.
  void update(std::span<const EkfObservation> observations, const Eigen::MatrixXd& S) {
    require_settled();
    if (observations.empty()) return;
    const int n = dimension();
    const int k = static_cast<int>(observations.size());
    Eigen::MatrixXd PHt(n, 2 * k);
    Eigen::VectorXd nu(2 * k);
    for (int a = 0; a < k; ++a) {
      const EkfObservation& o = observations[a];
      ARBOR_CHECK(o.cross != nullptr && o.cross->cols() == n, "EKF observation {} lacks its rows H P", a);
      PHt.middleCols<2>(2 * a) = o.cross->transpose();
      nu.segment<2>(2 * a) = o.innovation;
    }
    const Eigen::LLT<Eigen::MatrixXd> llt(S);
    if (llt.info() != Eigen::Success)  // huge motion noise or controls within the scenario limits (see the header)
      throw NumericalBreakdown(
          fmt::format("EKF innovation covariance of {} measurements is not positive definite", k));
    mean_.head(n) += PHt * llt.solve(nu);
    mean_(2) = wrap_angle(mean_(2));
    const Eigen::MatrixXd Vt = llt.matrixL().solve(PHt.transpose());  // L^-1 H P, 2k x n
    auto P = cov_.topLeftCorner(n, n);
    P.selfadjointView<Eigen::Lower>().rankUpdate(Vt.transpose(), -1.0);
    mirror_lower(n);
  }

  // A new landmark from measurement z at the current pose, with its cross covariances (Table 10.1's
  // initialisation, linearised): m = h^-1(x, z), P_mm = J_x P_xx J_x^T + J_z R J_z^T, P_m* = J_x P_x*.
  // ids must arrive above every id held.
  void add_landmark(LandmarkId id, const Vec2& z, const Mat2& R) {
    require_settled();
    ARBOR_CHECK(ids_.empty() || id > ids_.back(), "EKF landmark {} does not come after {}", id, ids_.back());
    const Pose2 x = pose();
    Mat2 J_z;
    const Vec2 m = range_bearing_inverse(x, z, &J_z);
    Mat23 J_x;
    J_x << 1, 0, -(m.y() - x.y), 0, 1, m.x() - x.x;
    Mat2 measurement_part = J_z * R * J_z.transpose();
    measurement_part = 0.5 * (measurement_part + measurement_part.transpose());
    floor_covariance(&measurement_part);  // rank 1 at zero range
    const int n = dimension();
    reserve(n + 2);
    const MeasurementCross cross = J_x * cov_.topLeftCorner(3, n);
    cov_.block(n, 0, 2, n) = cross;
    cov_.block(0, n, n, 2) = cross.transpose();
    Mat2 own = cross.leftCols<3>() * J_x.transpose() + measurement_part;
    cov_.block<2, 2>(n, n) = 0.5 * (own + own.transpose());
    mean_.segment<2>(n) = m;
    ids_.push_back(id);
  }

  // Room for this many landmarks without regrowing (a prior map of 10^4 landmarks: doubling would hold up to
  // four times the covariance's 3.2 GB while it copies).
  void reserve_landmarks(int count) { reserve(3 + 2 * count); }

  // A landmark known before the run (a prior map): independent of the pose and of the others.
  void add_known_landmark(LandmarkId id, const Vec2& mean, const Mat2& covariance) {
    require_settled();
    ARBOR_CHECK(ids_.empty() || id > ids_.back(), "EKF landmark {} does not come after {}", id, ids_.back());
    const int n = dimension();
    reserve(n + 2);
    cov_.block(n, 0, 2, n).setZero();
    cov_.block(0, n, n, 2).setZero();
    cov_.block<2, 2>(n, n) = covariance;
    mean_.segment<2>(n) = mean;
    ids_.push_back(id);
  }

  // Marginalises the landmarks out (their rows and columns are dropped), keeping the others in order.
  void remove(std::span<const LandmarkId> removed) {
    require_settled();
    if (removed.empty()) return;
    std::vector<int> keep{0, 1, 2};  // state rows kept, in order
    std::vector<LandmarkId> ids;
    for (int slot = 0; slot < landmarks(); ++slot) {
      if (std::find(removed.begin(), removed.end(), ids_[slot]) != removed.end()) continue;
      ids.push_back(ids_[slot]);
      keep.push_back(row(slot));
      keep.push_back(row(slot) + 1);
    }
    const int n = static_cast<int>(keep.size());
    for (int c = 0; c < n; ++c) {  // in place: keep is increasing, so every source lies at or after its target
      for (int r = 0; r < n; ++r) cov_(r, c) = cov_(keep[r], keep[c]);
      mean_(c) = mean_(keep[c]);
    }
    ids_ = std::move(ids);
  }

 private:
  static int row(int slot) { return 3 + 2 * slot; }

  void require_settled() const { ARBOR_CHECK(pending_G_ == Mat3::Identity(), "EKF cross covariance used before settle()"); }

  // Room for a state of dimension n; capacity doubles, so adding a landmark copies O(n) entries, not O(n^2).
  void reserve(int n) {
    if (n <= capacity_) return;
    const int capacity = std::max(n, 2 * capacity_);
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(capacity, capacity);
    Eigen::VectorXd mean = Eigen::VectorXd::Zero(capacity);
    if (capacity_ > 0) {
      cov.topLeftCorner(capacity_, capacity_) = cov_;
      mean.head(capacity_) = mean_;
    }
    cov_.swap(cov);
    mean_.swap(mean);
    capacity_ = capacity;
  }

  // Copies the lower triangle of the leading n x n block onto the upper one, a tile at a time: a row of a
  // column-major matrix is strided, and copying row by row missed the cache at every element (at N = 3000 it
  // took longer than the update itself).
  void mirror_lower(int n) {
    constexpr int kTile = 64;
    for (int c0 = 0; c0 < n; c0 += kTile) {
      const int width = std::min(kTile, n - c0);
      for (int r0 = 0; r0 < c0; r0 += kTile) {
        const int height = std::min(kTile, n - r0);
        cov_.block(r0, c0, std::min(height, c0 - r0), width) = cov_.block(c0, r0, width, std::min(height, c0 - r0)).transpose();
      }
      for (int c = c0 + 1; c < c0 + width; ++c) cov_.col(c).segment(c0, c - c0) = cov_.row(c).segment(c0, c - c0).transpose();
    }
  }

  Eigen::VectorXd mean_;
  Eigen::MatrixXd cov_;  // capacity_ x capacity_; the leading dimension() block is the covariance
  int capacity_ = 0;
  std::vector<LandmarkId> ids_;  // ascending: slot order
  Mat3 pending_G_ = Mat3::Identity();
};

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_EKF_STATE_H_
