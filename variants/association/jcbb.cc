// JCBB search with an incrementally extended Cholesky factor of the joint innovation covariance.
#include "variants/association/jcbb.h"

#include <algorithm>
#include <cmath>

#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

constexpr int kTabulatedDof = 512;

// One search: the problem, the scratch and the best hypothesis so far.
class JcbbSearch {
 public:
  JcbbSearch(const AssociationProblem& problem, JcbbScratch& s, const ChiSquareTable& joint_gate,
             std::int64_t max_hypotheses, std::int64_t max_work, AssociationStats* stats)
      : p_(problem), s_(s), joint_gate_(joint_gate), max_hypotheses_(max_hypotheses), max_work_(max_work), stats_(stats),
        levels_(static_cast<int>(s.order.size())),
        coupled_(problem.joint_covariance.size() > 0 || !problem.P.isZero(0.0)) {}

  void run() {
    s_.current.assign(levels_, -1);
    s_.best.assign(levels_, -1);
    s_.used.assign(p_.candidates.size(), 0);
    s_.paired.resize(levels_);
    information_form_ = coupled_ && p_.joint_covariance.size() == 0 && prepare_information_form();
    if (coupled_ && !information_form_) {
      // Only the Cholesky form needs the (2m)^2 factor: allocated for it alone (20k measurements would ask
      // for 12.8 GB).
      const std::size_t dim = 2 * static_cast<std::size_t>(levels_);
      s_.L.assign(dim * dim, 0.0);
      s_.y.assign(dim, 0.0);
      s_.W.assign(dim * 2, 0.0);
      if (p_.joint_covariance.size() == 0) {
        s_.HP.resize(p_.candidates.size());
        for (std::size_t j = 0; j < p_.candidates.size(); ++j) s_.HP[j] = p_.candidates[j].H_pose * p_.P;
      }
    }
    search(0, 0, 0.0);
  }

 private:
  // Per-candidate terms of the information form; false (use the Cholesky form) when some individual S_j is
  // not invertible. That test is over every candidate, as it always was; the terms themselves only for the
  // candidates some level lists, the only ones the search reads (on Victoria Park the terms of every
  // candidate in the widened view were most of this search's own time).
  bool prepare_information_form() {
    for (const AssociationCandidate& c : p_.candidates)
      if (!association::candidate_information_exists(c)) return false;
    s_.information.resize(p_.candidates.size());
    s_.has_information.assign(p_.candidates.size(), 0);
    for (const int j : s_.list) {
      if (s_.has_information[j]) continue;
      s_.has_information[j] = 1;
      association::candidate_information(p_.candidates[j], &s_.information[j]);
    }
    s_.sums.assign(static_cast<std::size_t>(levels_) + 1, association::JointInformation{});
    return true;
  }

  // The information-form extension: writes the sums for depth + 1 and returns the new joint distance.
  double extend_information(int depth, int k, int j, double d2) {
    const Vec2 nu = range_bearing_innovation(p_.measurements[s_.order[k]].z, p_.candidates[j].z_hat);
    s_.sums[depth + 1] = s_.sums[depth].plus(s_.information[j], nu);
    // Exact arithmetic never lets D2 fall along a branch; rounding must not either (the bound relies on it).
    return std::max(d2, s_.sums[depth + 1].distance(p_.P));
  }

  // C(a, b) for a != b: H_a P H_b^T with G_a = H_a P precomputed once per candidate (or the given joint block).
  Mat2 cross(int a, int b) const {
    if (p_.joint_covariance.size() > 0) return p_.joint_covariance.block<2, 2>(2 * a, 2 * b);
    return s_.HP[a] * p_.candidates[b].H_pose.transpose();
  }

  double& L(int r, int c) { return s_.L[static_cast<std::size_t>(r) * 2 * levels_ + c]; }

  // Extends the factor for the hypothesis with `depth` pairings by candidate j for measurement level k.
  // Writes the new block row of L and of y (rows 2 depth, 2 depth + 1) and returns the new joint distance,
  // or -1 when the Schur complement is not positive definite (numerically incompatible).
  double extend(int depth, int k, int j, double d2, double individual_d2) {
    if (!coupled_) {
      // P = 0: the joint covariance is block-diagonal, so the joint distance is the sum of the individual ones.
      return d2 + individual_d2;
    }
    if (information_form_) return extend_information(depth, k, j, d2);
    const Vec2 nu = range_bearing_innovation(p_.measurements[s_.order[k]].z, p_.candidates[j].z_hat);
    const int n = 2 * depth;
    work_ += static_cast<std::int64_t>(n) * n;
    // B = C(paired, j); W = L^-1 B by forward substitution, O(depth^2).
    double* W = s_.W.data();
    for (int t = 0; t < depth; ++t) {
      const Mat2 b = cross(s_.paired[t], j);
      W[2 * (2 * t) + 0] = b(0, 0);
      W[2 * (2 * t) + 1] = b(0, 1);
      W[2 * (2 * t + 1) + 0] = b(1, 0);
      W[2 * (2 * t + 1) + 1] = b(1, 1);
    }
    for (int r = 0; r < n; ++r) {
      double w0 = W[2 * r], w1 = W[2 * r + 1];
      const double* row = &L(r, 0);
      for (int c = 0; c < r; ++c) {
        w0 -= row[c] * W[2 * c];
        w1 -= row[c] * W[2 * c + 1];
      }
      W[2 * r] = w0 / row[r];
      W[2 * r + 1] = w1 / row[r];
    }
    // Schur complement D = C_jj - W^T W and its 2x2 Cholesky factor L22.
    Mat2 D = p_.innovation_covariance(j, j);
    D = 0.5 * (D + D.transpose());
    Vec2 t = nu;
    for (int r = 0; r < n; ++r) {
      D(0, 0) -= W[2 * r] * W[2 * r];
      D(0, 1) -= W[2 * r] * W[2 * r + 1];
      D(1, 1) -= W[2 * r + 1] * W[2 * r + 1];
      t(0) -= W[2 * r] * s_.y[r];
      t(1) -= W[2 * r + 1] * s_.y[r];
    }
    if (!(D(0, 0) > 0.0)) return -1.0;
    const double l11 = std::sqrt(D(0, 0));
    const double l21 = D(0, 1) / l11;
    const double s22 = D(1, 1) - l21 * l21;
    if (!(s22 > 0.0)) return -1.0;
    const double l22 = std::sqrt(s22);
    const double y0 = t(0) / l11;
    const double y1 = (t(1) - l21 * y0) / l22;
    // Commit the block row; a rejected or abandoned pairing is simply overwritten by the next one.
    double* row0 = &L(n, 0);
    double* row1 = &L(n + 1, 0);
    for (int c = 0; c < n; ++c) {
      row0[c] = W[2 * c];
      row1[c] = W[2 * c + 1];
    }
    row0[n] = l11;
    row0[n + 1] = 0.0;
    row1[n] = l21;
    row1[n + 1] = l22;
    s_.y[n] = y0;
    s_.y[n + 1] = y1;
    return d2 + y0 * y0 + y1 * y1;
  }

  // Levels after k that still have an unused compatible candidate: a tighter bound than the static count of
  // levels with any compatible candidate, since candidates taken by the hypothesis cannot pair again.
  int pairable_after(int k) {
    work_ += levels_ - k;
    int count = 0;
    for (int l = k + 1; l < levels_; ++l) {
      for (int e = s_.list_begin[l]; e < s_.list_begin[l + 1]; ++e) {
        if (!s_.used[s_.list[e]]) {
          ++count;
          break;
        }
      }
    }
    return count;
  }

  // True when a hypothesis with `pairings` pairings and distance >= d2 could still beat the best.
  bool can_beat(int pairings, double d2) const {
    return pairings > best_pairings_ || (pairings == best_pairings_ && d2 <= best_d2_);
  }

  void consider(int depth, double d2) {
    bool better = depth > best_pairings_ || (depth == best_pairings_ && d2 < best_d2_);
    if (!better && depth == best_pairings_ && d2 == best_d2_) {
      // Exact tie: the lower landmark ids, level by level.
      for (int k = 0; k < levels_; ++k) {
        const int a = s_.current[k], b = s_.best[k];
        if (a == b) continue;
        const LandmarkId ia = a < 0 ? kNoLandmark : p_.candidates[a].id;
        const LandmarkId ib = b < 0 ? kNoLandmark : p_.candidates[b].id;
        better = ia < ib;
        break;
      }
    }
    if (!better) return;
    best_pairings_ = depth;
    best_d2_ = d2;
    s_.best = s_.current;
  }

  void search(int k, int depth, double d2) {
    if (stats_->hypotheses >= max_hypotheses_ || work_ + stats_->tests >= max_work_) {
      stats_->budget_exhausted = true;
      return;
    }
    ++stats_->hypotheses;
    if (k == levels_) {
      consider(depth, d2);
      return;
    }
    const int after = pairable_after(k);
    if (can_beat(depth + 1 + after, d2)) {
      for (int e = s_.list_begin[k]; e < s_.list_begin[k + 1]; ++e) {
        const int j = s_.list[e];
        if (s_.used[j]) continue;
        ++stats_->tests;
        const double d2_new = extend(depth, k, j, d2, s_.list_d2[e]);
        if (d2_new < 0.0 || d2_new > joint_gate_(2 * (depth + 1))) continue;
        if (!can_beat(depth + 1 + after, d2_new)) continue;
        s_.used[j] = 1;
        s_.current[k] = j;
        s_.paired[depth] = j;
        search(k + 1, depth + 1, d2_new);
        s_.used[j] = 0;
        s_.current[k] = -1;
        if (stats_->budget_exhausted) return;
      }
    }
    if (can_beat(depth + after, d2)) search(k + 1, depth, d2);
  }

  const AssociationProblem& p_;
  JcbbScratch& s_;
  const ChiSquareTable& joint_gate_;
  std::int64_t max_hypotheses_;
  std::int64_t max_work_;
  std::int64_t work_ = 0;  // factor updates and candidate scans; each test counts one more (stats_->tests)
  AssociationStats* stats_;
  int levels_;
  bool coupled_;
  bool information_form_ = false;
  int best_pairings_ = -1;
  double best_d2_ = 0.0;
};

}  // namespace

Jcbb::Jcbb(const AssociationOptions& options)
    : gate_(chi_square_quantile(options.gate_probability, 2)),
      new_landmark_gate_(chi_square_quantile(options.new_landmark_probability, 2)),
      max_hypotheses_(options.max_hypotheses),
      max_work_(options.max_work),
      joint_gate_(options.gate_probability, kTabulatedDof) {}

void Jcbb::solve(const AssociationProblem& problem, Scratch& s, AssociationResult& result) const {
  const int m = static_cast<int>(problem.measurements.size());
  result.stats = {};
  association::gate_individually(problem, gate_, new_landmark_gate_, &s.gating, &result.stats);
  association::canonical_measurement_order(problem, &s.order);
  // The levels of the tree: the measurements with a compatible candidate, in canonical order. A measurement
  // without one can only stay unpaired; as a level it would only add a '*' node under every hypothesis.
  // (Most-constrained-first ordering was measured too: fewer nodes on the design problems, n = 500, median
  // 549 -> 380, but a worse filter on the cluttered test worlds, since which prefixes must pass their own
  // joint gate changes with the order.)
  const auto count_of = [&](int i) { return s.gating.first[i + 1] - s.gating.first[i]; };
  s.order.erase(std::remove_if(s.order.begin(), s.order.end(), [&](int i) { return count_of(i) == 0; }),
                s.order.end());
  const int levels = static_cast<int>(s.order.size());
  // Compatible candidates per level, most likely first so that good hypotheses are found early.
  s.list.clear();
  s.list_d2.clear();
  s.list_begin.assign(levels + 1, 0);
  for (int k = 0; k < levels; ++k) {
    s.list_begin[k] = static_cast<int>(s.list.size());
    const int i = s.order[k];
    auto* begin = s.gating.pairs.data() + s.gating.first[i];
    auto* end = s.gating.pairs.data() + s.gating.first[i + 1];
    std::sort(begin, end, [&](const association::GatedPair& a, const association::GatedPair& b) {
      if (a.d2 != b.d2) return a.d2 < b.d2;
      return problem.candidates[a.candidate].id < problem.candidates[b.candidate].id;
    });
    for (auto* g = begin; g != end; ++g) {
      s.list.push_back(g->candidate);
      s.list_d2.push_back(g->d2);
    }
  }
  s.list_begin[levels] = static_cast<int>(s.list.size());

  JcbbSearch search(problem, s, joint_gate_, max_hypotheses_, max_work_, &result.stats);
  search.run();

  result.pairing.assign(m, association::kUnassigned);
  for (int k = 0; k < levels; ++k)
    if (s.best[k] >= 0) result.pairing[s.order[k]] = problem.candidates[s.best[k]].id;
  association::finish_unpaired(s.gating.near_any, &result.pairing);
}

}  // namespace arbor
