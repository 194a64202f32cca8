// Random association problems with ground truth, and distance-based localities.
#include "variants/association/problem_generator.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <unordered_map>

#include <Eigen/Cholesky>

#include "core/check.h"
#include "core/engine/rng.h"
#include "core/math/angles.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

Vec2 sample_gaussian(std::mt19937_64& rng, const Mat2& cov) {
  std::normal_distribution<double> normal(0.0, 1.0);
  const Eigen::LLT<Mat2> llt(cov);
  const Vec2 u = draw_vec2([&] { return normal(rng); });
  return llt.matrixL() * u;
}

}  // namespace

GeneratedProblem generate_association_problem(const ProblemGeneratorOptions& o) {
  ARBOR_CHECK(o.observations >= 0 && o.observations <= o.landmarks, "observations {} must be in [0, landmarks {}]",
              o.observations, o.landmarks);
  std::mt19937_64 rng(o.seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  GeneratedProblem g;
  const int n = o.landmarks;
  const double side = std::sqrt(n / o.density);

  g.true_landmarks.resize(n);
  for (auto& p : g.true_landmarks) p = side * draw_vec2([&] { return unit(rng); });
  g.true_pose = {0.5 * side, 0.5 * side, wrap_angle(kPi * (2.0 * unit(rng) - 1.0))};
  const Vec3 pose_noise = o.pose_sigma.cwiseProduct(draw_vec3([&] { return normal(rng); }));
  g.prior_pose = Pose2::from_vector(g.true_pose.vector() + pose_noise);

  AssociationProblem& p = g.problem;
  p.R = Vec2(o.range_sigma * o.range_sigma, o.bearing_sigma * o.bearing_sigma).asDiagonal();
  p.P = o.pose_sigma.cwiseProduct(o.pose_sigma).asDiagonal();
  p.signature_sigma = o.signature_sigma;
  const bool signatures = std::isfinite(o.signature_sigma);
  std::vector<float> true_signature(n, std::numeric_limits<float>::quiet_NaN());

  p.candidates.resize(n);
  for (int j = 0; j < n; ++j) {
    AssociationCandidate& c = p.candidates[j];
    c.id = j;
    // Sigma_j: random principal axes; the map mean is off the truth by a draw from it (consistent estimate).
    const double s1 = o.landmark_sigma_min + (o.landmark_sigma_max - o.landmark_sigma_min) * unit(rng);
    const double s2 = o.landmark_sigma_min + (o.landmark_sigma_max - o.landmark_sigma_min) * unit(rng);
    const double a = kPi * unit(rng);
    Mat2 rot;
    rot << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
    c.position_cov = rot * Vec2(s1 * s1, s2 * s2).asDiagonal() * rot.transpose();
    c.position = g.true_landmarks[j] + sample_gaussian(rng, c.position_cov);
    Mat2 H;
    c.z_hat = range_bearing_predict(g.prior_pose, c.position, &H, &c.H_pose);
    c.S = H * c.position_cov * H.transpose() + p.R;
    if (signatures) {
      true_signature[j] = static_cast<float>(0.1 + 0.9 * unit(rng));
      c.signature = true_signature[j];
    }
  }
  assign_nearest_localities(&p, o.locality);

  // The m landmarks nearest the true pose are observed (ties by id).
  std::vector<int> by_distance(n);
  std::iota(by_distance.begin(), by_distance.end(), 0);
  const auto dist2 = [&](int j) { return (g.true_landmarks[j] - g.true_pose.position()).squaredNorm(); };
  std::partial_sort(by_distance.begin(), by_distance.begin() + o.observations, by_distance.end(),
                    [&](int a, int b) { return dist2(a) != dist2(b) ? dist2(a) < dist2(b) : a < b; });
  double max_range = 1.0;
  for (int k = 0; k < o.observations; ++k) {
    const int j = by_distance[k];
    AssociationMeasurement meas;
    meas.z = range_bearing_predict(g.true_pose, g.true_landmarks[j]);
    max_range = std::max(max_range, meas.z.x());
    meas.z += Vec2(o.range_sigma, o.bearing_sigma).cwiseProduct(draw_vec2([&] { return normal(rng); }));
    meas.z = Vec2(std::max(meas.z.x(), 0.0), wrap_angle(meas.z.y()));
    if (signatures) meas.signature = static_cast<float>(true_signature[j] + o.signature_sigma * normal(rng));
    p.measurements.push_back(meas);
    g.truth.push_back(j);
  }
  for (int k = 0; k < o.clutter; ++k) {
    AssociationMeasurement meas;
    const Vec2 u = draw_vec2([&] { return unit(rng); });
    meas.z = Vec2(max_range * std::sqrt(u.x()), wrap_angle(kPi * (2.0 * u.y() - 1.0)));
    if (signatures) meas.signature = static_cast<float>(0.1 + 0.9 * unit(rng));
    p.measurements.push_back(meas);
    g.truth.push_back(-1);
  }
  // Shuffle so that the input order says nothing about the truth.
  for (int i = static_cast<int>(p.measurements.size()) - 1; i > 0; --i) {
    const int k = static_cast<int>(unit(rng) * (i + 1)) % (i + 1);
    std::swap(p.measurements[i], p.measurements[k]);
    std::swap(g.truth[i], g.truth[k]);
  }
  return g;
}

AssociationCounts score_against_truth(const std::vector<LandmarkId>& pairing, const std::vector<LandmarkId>& truth) {
  AssociationCounts c;
  for (std::size_t i = 0; i < pairing.size() && i < truth.size(); ++i) {
    ++c.scored;
    if (pairing[i] >= 0) {
      (pairing[i] == truth[i] ? c.true_matches : c.false_matches) += 1;
    } else if (truth[i] >= 0) {
      ++c.missed_matches;
      if (pairing[i] == kNewLandmark) ++c.false_new;
    }
  }
  return c;
}

void assign_nearest_localities(AssociationProblem* problem, int k) {
  auto& cands = problem->candidates;
  const int n = static_cast<int>(cands.size());
  for (auto& c : cands) c.locality = LocalitySet();
  if (n < 2 || k <= 0) return;
  k = std::min({k, n - 1, LocalitySet::kCapacity});
  Vec2 lo = cands[0].position, hi = cands[0].position;
  for (const auto& c : cands) {
    lo = lo.cwiseMin(c.position);
    hi = hi.cwiseMax(c.position);
  }
  // About k+1 landmarks per cell, so rings of cells find the k nearest after a few steps.
  const double area = std::max((hi - lo).prod(), 1e-9);
  const double cell = std::max(std::sqrt(area * (k + 1) / n), 1e-6);
  const auto key = [&](int cx, int cy) { return (static_cast<std::int64_t>(cx) << 32) ^ static_cast<std::uint32_t>(cy); };
  std::unordered_map<std::int64_t, std::vector<int>> grid;
  const auto cell_of = [&](const Vec2& q) {
    return std::pair<int, int>(static_cast<int>(std::floor((q.x() - lo.x()) / cell)),
                               static_cast<int>(std::floor((q.y() - lo.y()) / cell)));
  };
  for (int j = 0; j < n; ++j) {
    const auto [cx, cy] = cell_of(cands[j].position);
    grid[key(cx, cy)].push_back(j);
  }
  const int max_ring = static_cast<int>(std::ceil((hi - lo).maxCoeff() / cell)) + 1;
  std::vector<std::pair<double, int>> found;
  for (int j = 0; j < n; ++j) {
    const auto [cx, cy] = cell_of(cands[j].position);
    found.clear();
    for (int ring = 0; ring <= max_ring; ++ring) {
      for (int dx = -ring; dx <= ring; ++dx)
        for (int dy = -ring; dy <= ring; ++dy) {
          if (std::max(std::abs(dx), std::abs(dy)) != ring) continue;
          const auto it = grid.find(key(cx + dx, cy + dy));
          if (it == grid.end()) continue;
          for (int h : it->second)
            if (h != j) found.push_back({(cands[h].position - cands[j].position).squaredNorm(), cands[h].id});
        }
      // Everything within ring * cell of the point has been seen; stop once the k-th nearest lies inside.
      if (static_cast<int>(found.size()) >= k) {
        std::nth_element(found.begin(), found.begin() + (k - 1), found.end());
        if (found[k - 1].first <= (ring * cell) * (ring * cell)) break;
      }
    }
    std::sort(found.begin(), found.end());
    for (int e = 0; e < k && e < static_cast<int>(found.size()); ++e) cands[j].locality.add(found[e].second);
  }
}

}  // namespace arbor
