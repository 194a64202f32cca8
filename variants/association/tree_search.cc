// Interpretation-tree search with unary (signature) and binary (pairwise distance) constraints, an optional
// locality restriction, pose verification of the best hypotheses and a gated completion.
#include "variants/association/tree_search.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <tuple>
#include <utility>

#include <Eigen/Cholesky>

#include "core/math/chi_square.h"
#include "core/models/range_bearing_model.h"
#include "variants/association/joint_compatibility.h"
#include "variants/association/joint_information.h"
#include "variants/association/rigid_alignment.h"

namespace arbor::association {
namespace {

// Variance floor for the distance constraint [m^2]: keeps exact (noise-free) problems well posed.
constexpr double kMinDistanceVariance = 1e-12;
// anchor_pairs' mark for a pair not yet computed.
constexpr double kNotComputed = std::numeric_limits<double>::quiet_NaN();
// The anchor index keeps one bit per level (a 64-bit mask); larger scans search without it.
constexpr int kMaxIndexedLevels = 64;
static_assert(LocalitySet::kCapacity <= 64, "the anchor index keeps one bit per locality feature");

class TreeSearch {
 public:
  using LevelPair = TreeScratch::LevelPair;

  TreeSearch(const AssociationProblem& problem, const TreeSettings& settings, TreeScratch& s,
             AssociationStats* stats)
      : p_(problem), set_(settings), s_(s), stats_(stats), m_(static_cast<int>(problem.measurements.size())),
        n_(static_cast<int>(problem.candidates.size())),
        signatures_(std::isfinite(problem.signature_sigma) && problem.signature_sigma > 0.0),
        joint_(problem.joint_covariance.size() > 0),
        ranking_(settings.check_prior ? kTreeHypothesesVerified : kTreeHypothesesVerifiedPoseFree),
        accept_count_(settings.check_prior || !(settings.accept_explained > 0.0)
                          ? 0
                          : std::max(kTreeMinAccepted, static_cast<int>(std::ceil(settings.accept_explained * m_)))) {}

  void prepare() {
    canonical_measurement_order(p_, &s_.order);
    s_.rank.resize(m_);
    for (int k = 0; k < m_; ++k) s_.rank[s_.order[k]] = k;
    s_.point.resize(m_);
    s_.point_cov.resize(m_);
    const Pose2 origin;
    for (int k = 0; k < m_; ++k) {
      const Vec2& z = p_.measurements[s_.order[k]].z;
      Mat2 J;
      s_.point[k] = range_bearing_inverse(origin, z, &J);
      s_.point_cov[k] = J * p_.R * J.transpose();
    }
    s_.position.resize(n_);
    s_.position_cov.resize(n_);
    for (int j = 0; j < n_; ++j) {
      s_.position[j] = p_.candidates[j].position;
      s_.position_cov[j] = p_.candidates[j].position_cov;
    }
    if (joint_) {
      s_.jacobian.resize(n_);
      for (int j = 0; j < n_; ++j) range_bearing_inverse(origin, p_.candidates[j].z_hat, &s_.jacobian[j]);
    }
    index_ids();
    reset_search();
    if (set_.check_prior) restrict_to_prior();
    if (!set_.use_locality) return;
    // Locality sets hold ids; the search needs candidate indices (candidates are sorted by id).
    s_.loc_begin.assign(n_ + 1, 0);
    s_.loc.clear();
    for (int j = 0; j < n_; ++j) {
      s_.loc_begin[j] = static_cast<int>(s_.loc.size());
      for (LandmarkId id : p_.candidates[j].locality) {
        const int g = index_of(id);
        if (g >= 0 && g != j) s_.loc.push_back(g);
      }
    }
    s_.loc_begin[n_] = static_cast<int>(s_.loc.size());
    s_.allowed.resize(m_ + 1);
    s_.open_levels.resize(m_ + 1);
    words_ = std::max(1, (m_ + 63) / 64);
    indexed_ = !set_.check_prior && !joint_ && m_ <= kMaxIndexedLevels;
    if (indexed_) index_anchors();
  }

  // The whole search. Every node of depth 0 is "unpaired up to level k, then anchor g at level k", so the
  // pose-free locality search may try those anchors in any order: it tries first the anchors whose locality
  // pairs at the most levels below them, which fills the ranking with strong hypotheses early; from the
  // first anchor that cannot enter the ranking on, none can (the bar only rises), and the search stops.
  // Among hypotheses with as many pairings the ranking keeps the first found, so ties may resolve
  // differently from the level order; the per-particle search (a prior) keeps the level order.
  void search_all() {
    if (!indexed_) {
      search(0, 0);
      return;
    }
    for (const TreeScratch::Anchor& a : s_.anchors) {
      if (stopped() || !can_enter(1 + a.reach)) break;
      branch(a.k, 0, a.g);
    }
  }

  void search(int k, int depth) {
    if (k == m_) {
      record(depth);
      return;
    }
    const int left = m_ - k - 1;
    if (!can_enter(depth + optimistic_extra(k, depth))) return;
    if (can_enter(depth + 1 + left)) {
      if (depth == 0 && set_.check_prior) {
        for (int e = s_.prior_begin[k]; e < s_.prior_begin[k + 1] && !stopped(); ++e)
          branch(k, depth, s_.prior_list[e]);
      } else if (!set_.use_locality || depth == 0) {
        for (int g = 0; g < n_ && !stopped(); ++g) branch(k, depth, g);
      } else {
        // allowed[depth] is stable while deeper levels rewrite allowed[depth + 1 ..].
        for (std::size_t e = 0; e < s_.allowed[depth].size() && !stopped(); ++e) {
          const int g = s_.allowed[depth][e];
          if (!s_.used[g] && level_open(s_.open_levels[depth].data() + e * words_, k))
            pair(k, depth, g, static_cast<int>(e));
        }
      }
      if (stopped()) return;
    }
    if (can_enter(depth + left)) search(k + 1, depth);
  }

  // Verifies the ranked hypotheses in order; the first that passes is completed and written to result.
  bool finish(AssociationResult& result, Pose2* pose_out) {
    result.pairing.assign(m_, kUnassigned);
    explained_ = 0;
    if (s_.ranked.empty()) {
      // No verified pose (a scan with one measurement never has one): per particle, the prior decides;
      // for relocalisation, nothing is paired.
      if (set_.check_prior) {
        complete_with_prior(&result.pairing);
        finish_unpaired(s_.prior.near_any, &result.pairing);
      } else {
        gate_individually(p_, set_.gate2, set_.new_landmark_gate, &s_.gating, stats_);
        finish_unpaired(s_.gating.near_any, &result.pairing);
      }
      return false;
    }
    // Each verified hypothesis is completed with its pose; the one whose pose explains the most measurements
    // wins (ties: rank order). A wrong pose that happens to fit a few features explains little else.
    std::vector<int> accepted;
    Pose2 pose;
    int best_count = -1;
    std::vector<char> near_any;
    for (std::size_t h = 0; h < s_.ranked.size(); ++h) {
      std::vector<int> candidate = s_.ranked[h];
      Pose2 candidate_pose = s_.ranked_pose[h];
      complete(&candidate, &candidate_pose);
      if (set_.check_prior && !consistent_with_prior(candidate)) continue;
      const int count = static_cast<int>(std::count_if(candidate.begin(), candidate.end(), [](int j) { return j >= 0; }));
      if (count > best_count) {
        best_count = count;
        accepted = std::move(candidate);
        pose = candidate_pose;
        near_any = s_.gating.near_any;
      }
    }
    explained_ = std::max(best_count, 0);
    if (best_count < 0) {
      // Every verified hypothesis contradicted the prior (only checked per particle): the prior decides alone.
      complete_with_prior(&result.pairing);
      finish_unpaired(s_.prior.near_any, &result.pairing);
      return false;
    }
    for (int k = 0; k < m_; ++k)
      if (accepted[k] >= 0) result.pairing[s_.order[k]] = p_.candidates[accepted[k]].id;
    if (set_.check_prior) {
      // Per particle, what the tree left open is paired with the prior, whose gates hold the pose
      // covariance (the completion at the fitted pose has none, so it misses pairings and starts duplicates).
      const std::vector<LandmarkId> tree_pairing = result.pairing;
      complete_with_prior(&result.pairing);
      if (!jointly_compatible(result.pairing)) result.pairing = tree_pairing;
      for (int i = 0; i < m_; ++i) near_any[i] |= s_.prior.near_any[i];
    }
    s_.gating.near_any = std::move(near_any);
    finish_unpaired(s_.gating.near_any, &result.pairing);
    if (pose_out) *pose_out = pose;
    return true;
  }

  // Pose-free: the winner explains less than TreeSettings::widen_below of the scan, and the ranking pruned part
  // of the tree, so the truth may be among what it pruned (see kTreeWideningFactor).
  bool explains_too_little() const {
    return !set_.check_prior && pruned_ && !stats_->budget_exhausted && !widened_ &&
           explained_ < std::ceil(set_.widen_below * m_);
  }

  // Searches again, keeping kTreeWideningFactor times as many verified hypotheses; the nodes of both passes
  // count in stats.hypotheses.
  void widen() {
    widened_ = true;
    ranking_ *= kTreeWideningFactor;
    accepted_ = false;
    pruned_ = false;
    reset_search();
  }

 private:
  // The search's state before its first node: nothing paired, nothing ranked.
  void reset_search() {
    s_.used.assign(n_, 0);
    s_.current.assign(m_, -1);
    s_.paired_level.assign(m_, -1);
    s_.ranked.clear();
    s_.ranked_pairings.clear();
    s_.ranked_pose.clear();
  }

  int index_of(LandmarkId id) const {
    if (!s_.index_by_id.empty()) {
      const LandmarkId e = id - p_.candidates.front().id;
      return e >= 0 && e < static_cast<LandmarkId>(s_.index_by_id.size()) ? s_.index_by_id[e] : -1;
    }
    const auto it = std::lower_bound(p_.candidates.begin(), p_.candidates.end(), id,
                                     [](const AssociationCandidate& c, LandmarkId v) { return c.id < v; });
    return it != p_.candidates.end() && it->id == id ? static_cast<int>(it - p_.candidates.begin()) : -1;
  }

  // Map ids are a creation serial, so a problem's candidate ids (sorted) are usually dense: then a table
  // finds a locality member's candidate in O(1); a binary search for each of the n c members was a tenth
  // of a pose-free search at n = 10^4.
  void index_ids() {
    s_.index_by_id.clear();
    if (n_ == 0) return;
    const LandmarkId span = p_.candidates.back().id - p_.candidates.front().id + 1;
    if (span > 4 * static_cast<LandmarkId>(n_) + 64) return;
    s_.index_by_id.assign(span, -1);
    for (int j = 0; j < n_; ++j) s_.index_by_id[p_.candidates[j].id - p_.candidates.front().id] = j;
  }

  // An upper bound on the pairings levels k.. can still add. In the locality search (after the first
  // pairing) only the open features can pair, and only at levels where one of them passes the constraints
  // against the pairings so far; without it the bound degenerates to "every level left", which makes the
  // search exponential in m through the '*' branches alone.
  int optimistic_extra(int k, int depth) {
    const int left = m_ - k;
    if (!set_.use_locality || depth == 0) return std::min(left, n_ - depth);
    const std::vector<int>& open = s_.allowed[depth];
    const std::uint64_t* masks = s_.open_levels[depth].data();
    const int limit = std::min(left, static_cast<int>(open.size()));
    int levels = 0;
    for (int w = k / 64; w < words_; ++w) {
      std::uint64_t any = 0;
      for (std::size_t i = 0; i < open.size(); ++i)
        if (!s_.used[open[i]]) any |= masks[i * words_ + w];
      if (w == k / 64) any &= ~std::uint64_t{0} << (k % 64);
      levels += std::popcount(any);
    }
    return std::min(levels, limit);
  }

  static bool level_open(const std::uint64_t* mask, int l) { return (mask[l / 64] >> (l % 64)) & 1u; }

  // Without a prior the root would try every candidate at every level, and each try would test its locality
  // against every later level: n m^2 c tests, 66-80 ms a search at n = 10^4 on a 2-core VM. A feature g at
  // level k and a feature h of its locality at level l can both pair only if their map distance matches the
  // measured distance of levels k and l within the binary gate. The measured pairs are few (m^2 / 2), so
  // each of the n c map pairs finds its matches by binary search among them, and the exact constraints are
  // tested on those alone. The levels where g has a partner are exactly what optimistic_extra counts below g, so an
  // anchor that cannot enter the ranking is skipped without changing the answer (only fewer nodes).
  void index_anchors() {
    s_.level_pairs.clear();
    s_.level_table.resize(static_cast<std::size_t>(m_) * m_);
    double widest_variance = 0.0, candidate_variance = 0.0;
    for (int k = 0; k < m_; ++k) {
      for (int l = k + 1; l < m_; ++l) {
        const LevelPair pair = level_pair(k, l);
        s_.level_table[static_cast<std::size_t>(k) * m_ + l] = pair;
        s_.level_pairs.push_back(pair);
        widest_variance = std::max(widest_variance, pair.variance);
      }
    }
    std::sort(s_.level_pairs.begin(), s_.level_pairs.end(), [](const auto& a, const auto& b) {
      return a.distance != b.distance ? a.distance < b.distance : std::tie(a.k, a.l) < std::tie(b.k, b.l);
    });
    for (const AssociationCandidate& c : p_.candidates)
      candidate_variance = std::max(candidate_variance, c.position_cov.trace());
    // The widest window binary() can accept: a projection of a covariance is at most its trace.
    const double reach =
        std::sqrt(set_.binary_gate * (kMinDistanceVariance + widest_variance + 2.0 * candidate_variance));
    s_.anchor_levels.assign(static_cast<std::size_t>(m_) * n_, 0);
    s_.anchor_features.assign(static_cast<std::size_t>(m_) * n_, 0);
    s_.edge_distance.resize(s_.loc.size());
    for (int g = 0; g < n_; ++g) {
      for (int e = s_.loc_begin[g]; e < s_.loc_begin[g + 1]; ++e) {
        const int h = s_.loc[e];
        const TreeScratch::MapDistance map = s_.edge_distance[e] = map_distance(g, h);
        const double lm = map.distance;
        auto it = std::lower_bound(s_.level_pairs.begin(), s_.level_pairs.end(), lm - reach,
                                   [](const auto& pair, double v) { return pair.distance < v; });
        for (; it != s_.level_pairs.end() && it->distance <= lm + reach; ++it) {
          ++stats_->tests;
          // binary(k, g, l, h), its terms computed once per measured pair and once per feature pair.
          if (!distances_match(*it, map)) continue;
          if (unary(it->k, g) && unary(it->l, h)) {
            s_.anchor_levels[static_cast<std::size_t>(g) * m_ + it->k] |= std::uint64_t{1} << it->l;
            s_.anchor_features[static_cast<std::size_t>(g) * m_ + it->k] |= std::uint64_t{1} << (e - s_.loc_begin[g]);
          }
        }
      }
    }
    // Most reach first, then (k, g) ascending: a counting sort on reach (at most 64) over the anchors
    // listed in (k, g) order, since a comparison sort of the 10^4-10^5 anchors was a tenth of a search.
    std::array<int, 66> first{};
    for (std::size_t e = 0; e < s_.anchor_levels.size(); ++e)
      if (s_.anchor_levels[e] != 0) ++first[kMaxIndexedLevels + 1 - anchor_reach(e)];
    int total = 0;
    for (int& f : first) total += std::exchange(f, total);
    s_.anchors.resize(total);
    for (int k = 0; k < m_; ++k) {
      for (int g = 0; g < n_; ++g) {
        const std::size_t e = static_cast<std::size_t>(g) * m_ + k;
        if (s_.anchor_levels[e] == 0) continue;
        const int reach = anchor_reach(e);
        s_.anchors[first[kMaxIndexedLevels + 1 - reach]++] = {reach, k, g};
      }
    }
  }

  // Pairings anchor e = g * m + k can add below it: levels with a partner, at most its partners.
  int anchor_reach(std::size_t e) const {
    return std::min(std::popcount(s_.anchor_levels[e]), std::popcount(s_.anchor_features[e]));
  }

  // Per particle the answer must agree with the prior (consistent_with_prior), so a pairing the prior
  // puts outside even the new-landmark gate can never be part of it: the tree skips it, and tries as
  // anchors only the candidates the prediction allows.
  // The gating is kept for the completion in finish(), which pairs within the (usually tighter) pairing gate.
  void restrict_to_prior() {
    gate_individually(p_, std::max(set_.gate2, set_.new_landmark_gate), set_.new_landmark_gate, &s_.prior, stats_);
    s_.prior_ok.assign(static_cast<std::size_t>(m_) * n_, 0);
    for (const GatedPair& g : s_.prior.pairs)
      if (g.d2 <= set_.new_landmark_gate) s_.prior_ok[static_cast<std::size_t>(s_.rank[g.measurement]) * n_ + g.candidate] = 1;
    s_.prior_begin.assign(m_ + 1, 0);
    s_.prior_list.clear();
    for (int k = 0; k < m_; ++k) {
      s_.prior_begin[k] = static_cast<int>(s_.prior_list.size());
      for (int j = 0; j < n_; ++j)
        if (s_.prior_ok[static_cast<std::size_t>(k) * n_ + j]) s_.prior_list.push_back(j);
    }
    s_.prior_begin[m_] = static_cast<int>(s_.prior_list.size());
  }

  // Unary and binary constraints of candidate g at level k against the `depth` pairings so far.
  bool passes(int k, int depth, int g) {
    if (set_.check_prior && !s_.prior_ok[static_cast<std::size_t>(k) * n_ + g]) return false;
    ++stats_->tests;
    if (!unary(k, g)) return false;
    for (int t = 0; t < depth; ++t) {
      const int ka = s_.paired_level[t];
      ++stats_->tests;
      if (!binary(ka, s_.current[ka], k, g)) return false;
    }
    return true;
  }

  // The search ends at its budget, or (pose-free, TreeSettings::accept_explained) at a pose that explains
  // enough of the scan.
  bool stopped() const { return stats_->budget_exhausted || accepted_; }

  bool can_enter(int pairings) {
    if (pairings < kTreeMinPairings) return false;
    if (static_cast<int>(s_.ranked.size()) < ranking_ || pairings > s_.ranked_pairings.back()) return true;
    pruned_ = true;
    return false;
  }

  // Unary constraint: signatures agree within the gate (when the sensor gives them).
  bool unary(int k, int g) const {
    if (!signatures_) return true;
    const double a = p_.measurements[s_.order[k]].signature, b = p_.candidates[g].signature;
    if (std::isnan(a) || std::isnan(b)) return true;
    const double d = a - b;
    return d * d <= set_.binary_gate * p_.signature_sigma * p_.signature_sigma;
  }

  // Binary constraint (Grimson): |p_a - p_b| must match |m_f - m_g| (ka < kb). The variance of the difference is the
  // sum of both point covariances projected on the measured direction and both landmark covariances
  // projected on the map direction (first order).
  bool binary(int ka, int f, int kb, int g) const {
    return distances_match(measured_pair(ka, kb), map_distance(f, g));
  }

  // Levels ka < kb: their measured distance, from the table when the anchor index built one.
  LevelPair measured_pair(int ka, int kb) const {
    return indexed_ ? s_.level_table[static_cast<std::size_t>(ka) * m_ + kb] : level_pair(ka, kb);
  }

  // The map side of binary(ka, f, kb, h): the distance of features f and h and its variance.
  TreeScratch::MapDistance map_distance(int f, int h) const {
    const Vec2 dm = s_.position[f] - s_.position[h];
    const double lm = dm.norm();
    return {lm, feature_distance_variance(f, h, dm, lm)};
  }

  // map_distance(f, h) for members a (feature f) and b (feature h) of the anchor's locality of size c:
  // computed once per anchor.
  const TreeScratch::MapDistance& anchor_pair(int a, int b, std::size_t c, int f, int h) {
    TreeScratch::MapDistance& cached = s_.anchor_pairs[static_cast<std::size_t>(a) * c + b];
    if (std::isnan(cached.distance)) cached = map_distance(f, h);
    return cached;
  }

  // The binary gate on a measured distance and a map distance.
  bool distances_match(const LevelPair& measured, const TreeScratch::MapDistance& map) const {
    const double d = measured.distance - map.distance;
    return d * d <= set_.binary_gate * (measured.variance + map.variance);
  }

  // The measured distance of levels ka and kb and its variance, with the floor that keeps exact problems
  // well posed.
  LevelPair level_pair(int ka, int kb) const {
    const Vec2 dp = s_.point[ka] - s_.point[kb];
    const double lp = dp.norm();
    double var = kMinDistanceVariance;
    if (lp > 0.0) {
      const Vec2 u = dp / lp;
      var += u.dot((s_.point_cov[ka] + s_.point_cov[kb]) * u);
    }
    return {lp, var, ka, kb};
  }

  // The variance of the map distance lm = |dm|, dm = m_f - m_g, projected on its direction.
  double feature_distance_variance(int f, int g, const Vec2& dm, double lm) const {
    if (lm <= 0.0) return 0.0;
    const Vec2 v = dm / lm;
    Mat2 cov = s_.position_cov[f] + s_.position_cov[g];
    if (joint_) {
      // Positions recovered from predictions share the pose error, which cancels in their difference:
      // Cov(m_f - m_g) = Sigma_f + Sigma_g - X_fg - X_fg^T, X_fg = J_f C_fg J_g^T.
      const Mat2 x = s_.jacobian[f] * p_.joint_covariance.block<2, 2>(2 * f, 2 * g) * s_.jacobian[g].transpose();
      cov -= x + x.transpose();
    }
    return std::max(v.dot(cov * v), 0.0);
  }

  // A pairing at depth 0 (the anchor) or without locality: tests its constraints first.
  void branch(int k, int depth, int g) {
    if (s_.used[g] || !passes(k, depth, g)) return;
    pair(k, depth, g);
  }

  // Pairs g at level k, its constraints passed; slot: g's place in the open set allowed[depth] (-1 at depth 0).
  void pair(int k, int depth, int g, int slot = -1) {
    if (stats_->hypotheses >= set_.max_hypotheses || stats_->tests >= set_.max_work / kTreeTestWork) {
      stats_->budget_exhausted = true;
      return;
    }
    ++stats_->hypotheses;
    if (set_.use_locality) open_after(k, depth, g, slot);
    s_.used[g] = 1;
    s_.current[k] = g;
    s_.paired_level[depth] = k;
    search(k + 1, depth + 1);
    s_.used[g] = 0;
    s_.current[k] = -1;
  }

  // The open set after pairing g at level k, with the levels where each open feature still passes every
  // constraint: the parent's levels narrowed by the binary test against g, so each (feature, level) pair
  // is tested once per node rather than at every node below it.
  void open_after(int k, int depth, int g, int slot) {
    // The remaining measurements may pair only with features in the locality of the first paired feature
    // (the anchor), so the open set never exceeds c features: the bound n((c+1)^m - 1)/c + 1.
    std::vector<int>& next = s_.allowed[depth + 1];
    std::vector<std::uint64_t>& masks = s_.open_levels[depth + 1];
    next.clear();
    masks.clear();
    const int* begin = s_.loc.data() + s_.loc_begin[g];
    const int* end = s_.loc.data() + s_.loc_begin[g + 1];
    // Anchor rule: the open set stays the first paired feature's locality. Intersection rule: it shrinks
    // to the features covisible with every paired one.
    if (depth == 0) {
      const std::size_t c = static_cast<std::size_t>(end - begin);
      s_.anchor_pairs.assign(c * c, {kNotComputed, kNotComputed});
      // The anchor index already found the features and the levels that pass with g at k; only their
      // combinations need the test.
      const std::size_t anchor = static_cast<std::size_t>(g) * m_ + k;
      for (const int* h = begin; h != end; ++h) {
        next.push_back(*h);
        for (int w = 0; w < words_; ++w) masks.push_back(0);
        std::uint64_t* mask = masks.data() + masks.size() - words_;
        if (indexed_ && !((s_.anchor_features[anchor] >> (h - begin)) & 1u)) continue;
        const std::size_t edge = static_cast<std::size_t>(s_.loc_begin[g] + (h - begin));
        for (int l = k + 1; l < m_; ++l) {
          if (indexed_ && !((s_.anchor_levels[anchor] >> l) & 1u)) continue;
          if (set_.check_prior && !s_.prior_ok[static_cast<std::size_t>(l) * n_ + *h]) continue;
          ++stats_->tests;
          // binary(k, g, l, h); the anchor index holds the map side of the pair g, h.
          const bool fits = indexed_ ? distances_match(measured_pair(k, l), s_.edge_distance[edge])
                                     : binary(k, g, l, *h);
          if (unary(l, *h) && fits) mask[l / 64] |= std::uint64_t{1} << (l % 64);
        }
      }
      return;
    }
    const std::vector<int>& open = s_.allowed[depth];
    // Under the anchor rule the open set is the anchor's locality at every depth, so g and h are its members
    // `slot` and i, and their map distance is cached for the whole subtree.
    const bool cached = set_.anchor_only && slot >= 0;
    for (std::size_t i = 0; i < open.size(); ++i) {
      const int h = open[i];
      if (!set_.anchor_only && std::find(begin, end, h) == end) continue;
      const std::uint64_t* parent = s_.open_levels[depth].data() + i * words_;
      next.push_back(h);
      for (int w = 0; w < words_; ++w) masks.push_back(0);
      std::uint64_t* mask = masks.data() + masks.size() - words_;
      const TreeScratch::MapDistance* map_pair = nullptr;
      for (int w = k / 64; w < words_; ++w) {
        std::uint64_t bits = parent[w];
        if (w == k / 64) bits &= k % 64 == 63 ? 0 : ~std::uint64_t{0} << (k % 64 + 1);
        for (; bits != 0; bits &= bits - 1) {
          const int l = 64 * w + std::countr_zero(bits);
          ++stats_->tests;
          if (!cached) {
            if (binary(k, g, l, h)) mask[w] |= std::uint64_t{1} << (l % 64);
            continue;
          }
          if (map_pair == nullptr) map_pair = &anchor_pair(slot, static_cast<int>(i), open.size(), g, h);
          if (distances_match(measured_pair(k, l), *map_pair))
            mask[w] |= std::uint64_t{1} << (l % 64);
        }
      }
    }
  }

  // Gated nearest neighbour on the prior's predictions for the measurements still unassigned, over the
  // candidates not yet taken, decided as NearestNeighbor decides (pair_greedily). Per particle only: reads
  // the prior gating of restrict_to_prior().
  void complete_with_prior(std::vector<LandmarkId>* pairing) {
    std::fill(s_.used.begin(), s_.used.end(), 0);
    for (const LandmarkId id : *pairing)
      if (id >= 0) s_.used[index_of(id)] = 1;
    s_.completion.clear();
    for (const GatedPair& g : s_.prior.pairs)
      if (g.d2 <= set_.gate2) s_.completion.push_back(g);
    pair_greedily(p_, s_.rank, &s_.completion, &s_.used, pairing);
  }

  // The joint test with the particle's own predictions; pairing is per measurement, any negative entry
  // unpaired.
  bool jointly_compatible(const std::vector<LandmarkId>& pairing) {
    ++stats_->tests;
    if (p_.joint_covariance.size() == 0) {
      // The information form (O(k), joint_information.h): the dense form's (2k)^3 factorisation, called for
      // every verified hypothesis of every particle, was a quarter of a locality run's time.
      JointInformation sums;
      CandidateInformation c;
      int dof = 0;
      bool structured = true;
      for (std::size_t i = 0; i < pairing.size() && structured; ++i) {
        if (pairing[i] < 0) continue;
        const int j = index_of(pairing[i]);
        if (j < 0) return false;  // not a candidate of this problem
        const AssociationCandidate& cand = p_.candidates[j];
        structured = candidate_information(cand, &c);
        sums = sums.plus(c, range_bearing_innovation(p_.measurements[i].z, cand.z_hat));
        dof += 2;
      }
      if (structured) return dof == 0 || sums.distance(p_.P) <= set_.joint_gate(dof);
    }
    return joint_compatibility(p_, pairing, set_.joint_gate).compatible;
  }

  // Per-particle use: the pose-free answer must also pass the joint test with the particle's own predictions
  // (innovation covariance, pose covariance included), so a geometric coincidence elsewhere in the map cannot
  // pull a tracking particle away.
  bool consistent_with_prior(const std::vector<int>& h) {
    std::vector<LandmarkId> ids(m_, kNewLandmark);
    for (int k = 0; k < m_; ++k)
      if (h[k] >= 0) ids[s_.order[k]] = p_.candidates[h[k]].id;
    return jointly_compatible(ids);
  }

  // A complete interpretation is verified at once (closed-form pose, joint test), and only verified ones are
  // ranked: verifying "the best, then the next best" in rank order picks the same hypothesis, and pruning
  // against verified ones keeps geometric coincidences that fail verification from crowding the ranking.
  void record(int depth) {
    Pose2 pose;
    if (!verify(s_.current, &pose)) return;
    // Most pairings first; equal counts keep discovery order (deterministic: levels and candidates are
    // visited in canonical order).
    auto pos = std::upper_bound(s_.ranked_pairings.begin(), s_.ranked_pairings.end(), depth, std::greater<int>());
    const auto at = pos - s_.ranked_pairings.begin();
    s_.ranked_pairings.insert(pos, depth);
    s_.ranked.insert(s_.ranked.begin() + at, s_.current);
    s_.ranked_pose.insert(s_.ranked_pose.begin() + at, pose);
    if (static_cast<int>(s_.ranked.size()) > ranking_) {
      s_.ranked.pop_back();
      s_.ranked_pose.pop_back();
      s_.ranked_pairings.pop_back();
    }
    if (accept_count_ > 0 && at < ranking_) {
      std::vector<int>& h = s_.accept_trial;
      h = s_.current;
      complete(&h, &pose);
      accepted_ = std::count_if(h.begin(), h.end(), [](int j) { return j >= 0; }) >= accept_count_;
    }
  }

  // Pose from the pairings (closed form), then the joint test of the world-frame residuals
  //   r_k = world_T_robot * p_k - m_f,  C_k = R_theta Cov(p_k) R_theta^T + Sigma_f,
  // against chi2 with 2k - 3 dof (three pose parameters were fitted to the same residuals).
  bool verify(const std::vector<int>& h, Pose2* pose) {
    s_.fit_p.clear();
    s_.fit_q.clear();
    for (int k = 0; k < m_; ++k) {
      if (h[k] < 0) continue;
      s_.fit_p.push_back(s_.point[k]);
      s_.fit_q.push_back(s_.position[h[k]]);
    }
    const int pairs = static_cast<int>(s_.fit_p.size());
    if (pairs < kTreeMinPairings || !align_rigid_2d(s_.fit_p, s_.fit_q, pose)) return false;
    const double c = std::cos(pose->theta), s = std::sin(pose->theta);
    Mat2 rot;
    rot << c, -s, s, c;
    double d2 = 0.0;
    for (int k = 0; k < m_; ++k) {
      if (h[k] < 0) continue;
      const Vec2 r = pose->transform(s_.point[k]) - s_.position[h[k]];
      Mat2 inverse;
      if (!invert_spd2(rot * s_.point_cov[k] * rot.transpose() + s_.position_cov[h[k]], &inverse))
        return false;
      d2 += r.dot(inverse * r);
    }
    ++stats_->tests;
    return d2 <= set_.joint_gate(2 * pairs - 3);
  }

  // complete()'s index: the candidates by world x, and the widest candidate covariance trace. A candidate
  // without a finite position could never pass the gate, so it is left out (and cannot upset the sort).
  void index_by_x() {
    indexed_by_x_ = true;
    s_.by_x.clear();
    widest_candidate_trace_ = 0.0;
    for (int j = 0; j < n_; ++j) {
      const double x = s_.position[j].x();
      if (!std::isfinite(x)) continue;
      s_.by_x.push_back({x, j});
      widest_candidate_trace_ = std::max(widest_candidate_trace_, s_.position_cov[j].trace());
    }
    std::sort(s_.by_x.begin(), s_.by_x.end());
  }

  // With a verified pose, the measurements the (possibly locality-capped) search left open are gated against
  // the unused candidates in the world frame and paired greedily by distance; the completed hypothesis is
  // kept only if it still passes the joint test. The same pass decides NEW vs SPURIOUS for the rest.
  // Pose-free (TreeSettings::pair_again_at_pose), the whole scan is then paired again at the refitted pose,
  // as gated nearest neighbour at that pose would pair it, and that answer is kept when it pairs as many and
  // passes the joint test: the tree chose its pairings by distances alone, and a clutter point, or two
  // neighbouring landmarks swapped, can pass those. In 600 kidnappings at n = 10^4 (uniform world, seeds 1-12), 560 relocalised before; 571 with
  // this alone, 573 with the widening alone (kTreeWideningFactor 8), 585 with both, 591 with both and 64.
  void complete(std::vector<int>* h, Pose2* pose) {
    std::vector<int> extended = *h;
    Pose2 refit;
    if (pair_at(*pose, &extended) && verify(extended, &refit)) {
      *h = std::move(extended);
      *pose = refit;
    }
    if (set_.check_prior || !set_.pair_again_at_pose) return;
    // Gated with the fitted pose's covariance (the tree's 2-4 pairings leave the heading uncertain enough to
    // move a landmark at 20 m by decimetres); NEW vs SPURIOUS stays the completion's decision.
    const std::vector<char> near_any = s_.gating.near_any;
    std::vector<int> again(m_, -1);
    Mat3 pose_cov;
    if (fitted_pose_covariance(*h, *pose, &pose_cov) && pair_at(*pose, &again, &pose_cov) &&
        count_paired(again) >= count_paired(*h) && verify(again, &refit)) {
      *h = std::move(again);
      *pose = refit;
    }
    s_.gating.near_any = near_any;
  }

  // d(R p + t)/d(t, theta) for a measured point p, given R p.
  static Mat23 world_point_jacobian(const Vec2& rotated) {
    Mat23 J;
    J << 1.0, 0.0, -rotated.y(), 0.0, 1.0, rotated.x();
    return J;
  }

  // The covariance of the pose fitted to h's pairings (first order): the inverse of
  // sum_k J_k^T C_k^-1 J_k, J_k = world_point_jacobian, C_k as verify() weighs the residuals.
  bool fitted_pose_covariance(const std::vector<int>& h, const Pose2& pose, Mat3* cov) const {
    const double c = std::cos(pose.theta), s = std::sin(pose.theta);
    Mat2 rot;
    rot << c, -s, s, c;
    Mat3 information = Mat3::Zero();
    for (int k = 0; k < m_; ++k) {
      if (h[k] < 0) continue;
      const Mat23 J = world_point_jacobian(rot * s_.point[k]);
      Mat2 inverse;
      if (!invert_spd2(rot * s_.point_cov[k] * rot.transpose() + s_.position_cov[h[k]], &inverse)) return false;
      information += J.transpose() * inverse * J;
    }
    Eigen::LDLT<Mat3> ldlt(information);
    if (ldlt.info() != Eigen::Success || !(ldlt.vectorD().minCoeff() > 0.0)) return false;
    *cov = ldlt.solve(Mat3::Identity());
    return true;
  }

  static int count_paired(const std::vector<int>& h) {
    return static_cast<int>(std::count_if(h.begin(), h.end(), [](int j) { return j >= 0; }));
  }

  // Pairs the levels of *h still unpaired (-1) with the candidates *h leaves free, gated at `pose` and
  // taken greedily by distance; fills s_.gating.near_any. Returns whether it paired any.
  bool pair_at(const Pose2& pose, std::vector<int>* h, const Mat3* pose_cov = nullptr) {
    const double c = std::cos(pose.theta), s = std::sin(pose.theta);
    Mat2 rot;
    rot << c, -s, s, c;
    if (!indexed_by_x_) index_by_x();
    s_.gating.near_any.assign(m_, 0);
    s_.gating.pairs.clear();
    // Its own flags, cleared after use: during the search (early acceptance) s_.used holds the search's state.
    s_.taken.resize(n_, 0);
    for (int k = 0; k < m_; ++k)
      if ((*h)[k] >= 0) s_.taken[(*h)[k]] = 1;
    std::vector<char> near_level(m_, 0);
    const double widest_gate = std::max(set_.new_landmark_gate, set_.gate2);
    for (int k = 0; k < m_; ++k) {
      const Vec2 w = pose.transform(s_.point[k]);
      Mat2 cov_w = rot * s_.point_cov[k] * rot.transpose();
      if (pose_cov) {
        const Mat23 J = world_point_jacobian(rot * s_.point[k]);
        cov_w += J * *pose_cov * J.transpose();
      }
      const double trace_w = cov_w.trace();
      // No candidate beyond this x distance passes the trace bound below (padded against rounding in sqrt).
      const double radius = std::sqrt(widest_gate * (trace_w + widest_candidate_trace_)) * (1.0 + 1e-9) + 1e-12;
      auto it = std::lower_bound(s_.by_x.begin(), s_.by_x.end(), w.x() - radius,
                                 [](const std::pair<double, int>& c, double x) { return c.first < x; });
      for (; it != s_.by_x.end() && it->first <= w.x() + radius; ++it) {
        const int j = it->second;
        ++stats_->tests;
        const Vec2 r = w - s_.position[j];
        // r^T A^-1 r >= |r|^2 / lambda_max(A) >= |r|^2 / trace(A): far candidates are passed over without
        // inverting A, and the bound is exact, so no decision changes.
        if (r.squaredNorm() > widest_gate * (trace_w + s_.position_cov[j].trace())) continue;
        Mat2 inverse;
        if (!invert_spd2(cov_w + s_.position_cov[j], &inverse)) continue;
        const double d2 = r.dot(inverse * r);
        if (d2 <= set_.new_landmark_gate) near_level[k] = 1;
        if ((*h)[k] < 0 && !s_.taken[j] && d2 <= set_.gate2) s_.gating.pairs.push_back({d2, k, j});
      }
    }
    for (int k = 0; k < m_; ++k) s_.gating.near_any[s_.order[k]] = near_level[k];
    if (s_.gating.pairs.empty()) {
      release(*h);
      return false;
    }
    auto& pairs = s_.gating.pairs;
    std::sort(pairs.begin(), pairs.end(), [&](const GatedPair& a, const GatedPair& b) {
      if (a.d2 != b.d2) return a.d2 < b.d2;
      if (p_.candidates[a.candidate].id != p_.candidates[b.candidate].id)
        return p_.candidates[a.candidate].id < p_.candidates[b.candidate].id;
      return a.measurement < b.measurement;
    });
    for (const GatedPair& g : pairs) {
      if ((*h)[g.measurement] >= 0 || s_.taken[g.candidate]) continue;
      (*h)[g.measurement] = g.candidate;
      s_.taken[g.candidate] = 1;
    }
    release(*h);
    return true;
  }

  // Clears complete()'s flags of the candidates a hypothesis pairs.
  void release(const std::vector<int>& h) {
    for (int k = 0; k < m_; ++k)
      if (h[k] >= 0) s_.taken[h[k]] = 0;
  }

  const AssociationProblem& p_;
  const TreeSettings& set_;
  TreeScratch& s_;
  AssociationStats* stats_;
  int m_;
  int n_;
  bool signatures_;
  bool joint_;  // positions come from predictions with a joint covariance (exchange format)
  bool indexed_ = false;  // the root's anchors come from index_anchors()
  int words_ = 1;         // 64-bit words per level mask
  int ranking_;           // verified hypotheses kept
  int accept_count_;      // pose-free: measurements a completed pose must explain to end the search (0: never)
  bool accepted_ = false;
  bool pruned_ = false;    // the ranking's bar cut off part of the tree
  bool widened_ = false;   // widen() ran
  int explained_ = 0;      // measurements the winner's completed hypothesis pairs (set by finish())
  bool indexed_by_x_ = false;  // s_.by_x holds this problem's candidates
  double widest_candidate_trace_ = 0.0;  // set by index_by_x()
};

}  // namespace

void solve_tree(const AssociationProblem& problem, const TreeSettings& settings, TreeScratch& scratch,
                AssociationResult& result, Pose2* pose, bool* verified) {
  if (pose != nullptr && settings.check_prior) {
    // Relocalisation (a pose is asked for): the prior is not trusted.
    TreeSettings pose_free = settings;
    pose_free.check_prior = false;
    solve_tree(problem, pose_free, scratch, result, pose, verified);
    return;
  }
  result.stats = {};
  result.stats.hypotheses = 1;  // the empty hypothesis
  TreeSearch search(problem, settings, scratch, &result.stats);
  search.prepare();
  search.search_all();
  bool ok = search.finish(result, pose);
  if (search.explains_too_little()) {
    search.widen();
    search.search_all();
    ok = search.finish(result, pose);
  }
  if (verified) *verified = ok;
}

double locality_hypothesis_bound(int n, int m, int c) {
  if (c <= 0) return static_cast<double>(n) * m + 1.0;  // the limit c -> 0: one pairing at most
  return n * (std::pow(c + 1.0, m) - 1.0) / c + 1.0;
}

}  // namespace arbor::association
