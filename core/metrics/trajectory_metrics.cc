// ATE, landmark RMSE, NEES and dead reckoning (see trajectory_metrics.h).
#include "core/metrics/trajectory_metrics.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <Eigen/LU>

#include "core/math/chi_square.h"

namespace arbor {

std::optional<Pose2> interpolate_pose(const std::vector<TimedPose>& trajectory, double t) {
  if (trajectory.empty() || t < trajectory.front().time_s || t > trajectory.back().time_s) return std::nullopt;
  auto it = std::lower_bound(trajectory.begin(), trajectory.end(), t,
                             [](const TimedPose& p, double time) { return p.time_s < time; });
  if (it->time_s == t || it == trajectory.begin()) return it->pose;
  const TimedPose& b = *it;
  const TimedPose& a = *(it - 1);
  const double f = (t - a.time_s) / (b.time_s - a.time_s);
  return Pose2{a.pose.x + f * (b.pose.x - a.pose.x), a.pose.y + f * (b.pose.y - a.pose.y),
               wrap_angle(a.pose.theta + f * wrap_angle(b.pose.theta - a.pose.theta))};
}

Pose2 align_se2(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
  if (a.empty()) return {};
  Vec2 ca = Vec2::Zero(), cb = Vec2::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca /= a.size();
  cb /= b.size();
  // The optimal angle maximises sum (b_i - cb) . R (a_i - ca): atan2 of the summed cross and dot products.
  double cross = 0.0, dot = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec2 p = a[i] - ca, q = b[i] - cb;
    dot += p.dot(q);
    cross += p.x() * q.y() - p.y() * q.x();
  }
  const double theta = std::atan2(cross, dot);
  const double c = std::cos(theta), s = std::sin(theta);
  const Vec2 t = cb - Vec2(c * ca.x() - s * ca.y(), s * ca.x() + c * ca.y());
  return {t.x(), t.y(), theta};
}

std::optional<AteResult> absolute_trajectory_error(const std::vector<TimedPose>& estimate,
                                                   const std::vector<TimedPosition>& truth, bool align) {
  std::vector<Vec2> est, ref;
  for (const TimedPosition& g : truth) {
    const auto p = interpolate_pose(estimate, g.time_s);
    if (!p) continue;
    est.push_back(p->position());
    ref.push_back(g.position);
  }
  if (est.empty()) return std::nullopt;
  AteResult r;
  if (align) r.alignment = align_se2(est, ref);
  double sum = 0.0;
  for (std::size_t i = 0; i < est.size(); ++i) sum += (r.alignment.transform(est[i]) - ref[i]).squaredNorm();
  r.rmse_m = std::sqrt(sum / est.size());
  r.matched = static_cast<int>(est.size());
  return r;
}

std::vector<TimedPosition> truth_positions(const Scenario& scenario) {
  std::vector<TimedPosition> out;
  for (const auto& s : scenario.steps)
    if (s.truth_pose) out.push_back({s.time_s, s.truth_pose->position()});
  return out;
}

std::optional<double> landmark_rmse(const std::vector<Landmark>& map, const std::vector<TruthLandmark>& truth,
                                    const Pose2& alignment) {
  std::unordered_map<std::int32_t, Vec2> position;
  for (const auto& t : truth) position[t.id] = t.position;
  double sum = 0.0;
  int n = 0;
  for (const Landmark& lm : map) {
    auto it = position.find(lm.truth_label);
    if (lm.truth_label < 0 || it == position.end()) continue;
    sum += (alignment.transform(lm.mean) - it->second).squaredNorm();
    ++n;
  }
  if (n == 0) return std::nullopt;
  return std::sqrt(sum / n);
}

double pose_nees(const Pose2& estimate, const Mat3& covariance, const Pose2& truth) {
  const Vec3 e = pose_error(estimate, truth);
  // A collapsed particle set has a singular covariance; the floor keeps NEES finite (and very large).
  const Mat3 P = covariance + 1e-12 * Mat3::Identity();
  return e.dot(P.lu().solve(e));
}

double fraction_in_band(const std::vector<double>& values, NeesBand band) {
  if (values.empty()) return 0.0;
  std::size_t inside = 0;
  for (double v : values) inside += v >= band.low && v <= band.high;
  return static_cast<double>(inside) / static_cast<double>(values.size());
}

std::optional<std::size_t> consistency_horizon(const std::vector<double>& nees, int dof, int window) {
  const std::size_t w = static_cast<std::size_t>(window);
  if (window < 1 || nees.size() < w) return std::nullopt;
  const double low = chi_square_quantile(0.025, dof * window) / window;
  const double high = chi_square_quantile(0.975, dof * window) / window;
  std::size_t horizon = 0;  // one past the last sample whose window lies in the band
  for (std::size_t end = w; end <= nees.size(); ++end) {
    // Summed afresh (not a running sum): one NEES of 10^9 would leave its rounding in every later window.
    double sum = 0.0;
    for (std::size_t k = end - w; k < end; ++k) sum += nees[k];
    if (sum / window >= low && sum / window <= high) horizon = end;
  }
  return horizon;
}

std::vector<TimedPose> dead_reckoning(const Scenario& scenario) {
  std::vector<TimedPose> out;
  Pose2 pose = scenario.initial_pose;
  out.push_back({scenario.start_time_s, pose});
  for (const auto& s : scenario.steps) {
    pose = scenario.motion.apply(pose, s.control);
    out.push_back({s.time_s, pose});
  }
  return out;
}

}  // namespace arbor
