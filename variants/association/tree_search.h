// The interpretation-tree search shared by LocalityTree and InterpretationTree (Grimson 1990, "Object
// Recognition by Computer", ch. 3-4; locality after Ge & Lewis 2006, ch. 9). Pose-free: it compares the
// geometry of the measured points (robot frame) with that of the candidates' world positions.
#ifndef ARBOR_VARIANTS_ASSOCIATION_TREE_SEARCH_H_
#define ARBOR_VARIANTS_ASSOCIATION_TREE_SEARCH_H_

#include <cstdint>
#include <utility>
#include <vector>

#include "core/association/association_problem.h"
#include "core/math/chi_square.h"
#include "core/math/pose2.h"
#include "variants/association/association_common.h"

namespace arbor::association {

struct TreeScratch {
  IndividualGating gating;       // fallback classification when no hypothesis is verified
  std::vector<int> index_by_id;  // candidate index of id candidates[0].id + e, -1 absent (dense ids only)
  std::vector<int> order;        // level k of the tree is measurement order[k]
  std::vector<int> rank;         // rank[i]: the level of measurement i (order's inverse)
  // The candidates' world positions and covariances, packed: the searches read them for random candidates
  // (locality members), and a whole map's candidates are ten times larger than these.
  std::vector<Vec2> position;
  std::vector<Mat2> position_cov;
  std::vector<Vec2> point;       // measured point per level, robot frame
  std::vector<Mat2> point_cov;   // its covariance J R J^T
  std::vector<int> loc_begin;    // locality of candidate j as candidate indices: loc[loc_begin[j] ..)
  std::vector<int> loc;
  std::vector<std::vector<int>> allowed;  // allowed[d]: candidates open after d pairings (locality search)
  // open_levels[d][i * words + w]: word w of the levels where allowed[d][i] passes the unary constraint, the
  // prior and the binary constraint against each of the d pairings (levels after the last paired one only).
  std::vector<std::vector<std::uint64_t>> open_levels;
  std::vector<char> used;
  std::vector<int> current;      // candidate per level, -1 = unpaired
  std::vector<int> paired_level; // level of each pairing, in tree order
  std::vector<std::vector<int>> ranked;  // the best hypotheses found, most pairings first
  std::vector<int> ranked_pairings;
  std::vector<Pose2> ranked_pose;
  std::vector<Mat2> jacobian;    // d position / d z_hat per candidate (problems with a joint covariance)
  std::vector<Vec2> fit_p, fit_q;
  std::vector<Mat2> fit_cov;
  // Per-particle use: the individual gating under the prior (pose covariance included), once per problem;
  // prior_ok[k * n + j] says candidate j lies inside the new-landmark gate of the measurement at level k;
  // prior_begin/prior_list hold those candidates per level, the anchors tried at depth 0; completion holds
  // the pairs inside the pairing gate that the completion with the prior considers.
  IndividualGating prior;
  std::vector<char> prior_ok;
  std::vector<int> prior_begin, prior_list;
  std::vector<GatedPair> completion;
  // Pose-free locality search: anchor_levels[g * m + k] has bit l set when a feature of g's locality passes
  // the constraints at level l > k with g at level k; anchors lists every (k, g) with such a partner, the
  // most levels first; level_pairs holds the measured pairs (k < l) by distance.
  std::vector<std::uint64_t> anchor_levels, anchor_features;
  struct Anchor {
    int reach;  // pairings its locality can add: levels below with a partner, at most the partners
    int k, g;
  };
  std::vector<Anchor> anchors;
  struct LevelPair {
    double distance;
    double variance;  // of the distance, from the two measured points (as binary() projects it)
    int k, l;
  };
  std::vector<LevelPair> level_pairs;
  std::vector<LevelPair> level_table;  // level_table[k * m + l], k < l: the same pairs by level
  // A map distance |m_f - m_h| and its variance (as binary() projects it).
  struct MapDistance {
    double distance;
    double variance;
  };
  // Per locality entry loc[e] of candidate g: the map distance of g and loc[e], computed once by the anchor
  // index and read again by the anchors' first binary tests.
  std::vector<MapDistance> edge_distance;
  // Below an anchor (one paired feature, the open set its locality): anchor_pairs[a * c + b] holds the map
  // distance of locality members a and b, computed at their first binary test (NaN before), since every
  // deeper node tests the same few pairs again at other levels.
  std::vector<MapDistance> anchor_pairs;
  // The completion's spatial index: (world x, candidate) by x, so that each measurement examines only the
  // candidates within its widest gate; scanning the whole map for each of 32 verified hypotheses was a
  // quarter of a pose-free search at n = 10^4.
  std::vector<std::pair<double, int>> by_x;
  std::vector<char> taken;                   // the completion's candidate flags, all 0 between calls
  std::vector<int> accept_trial;             // a verified hypothesis completed during the search
};

struct TreeSettings {
  bool use_locality = true;
  bool anchor_only = false;  // open set = the first paired feature's locality (else the intersection over all)
  // Per-particle use: the answer must also be jointly compatible with the problem's own predictions (the
  // particle's pose and P). Ignored when solve_tree is asked for the pose (relocalisation: prior not trusted).
  bool check_prior = true;
  ChiSquareTable joint_gate;       // chi2(gate_probability, dof), cached (make_tree_settings fills it)
  double new_landmark_gate = 0.0;  // chi2(new_landmark_probability, 2)
  double gate2 = 0.0;              // chi2(gate_probability, 2)
  double binary_gate = 0.0;        // chi2(gate_probability, 1) for distances and signatures
  std::int64_t max_hypotheses = 0;
  std::int64_t max_work = 0;  // AssociationOptions::max_work: compatibility tests count kTreeTestWork each
  double accept_explained = 0.0;  // AssociationOptions::accept_explained (pose-free searches only)
  double widen_below = 0.0;       // AssociationOptions::widen_below (pose-free searches only)
  bool pair_again_at_pose = false;  // AssociationOptions::pair_again_at_pose (pose-free searches only)
};

// The work a compatibility test counts against TreeSettings::max_work: about its multiply-adds.
inline constexpr std::int64_t kTreeTestWork = 16;

// Verified hypotheses kept, most pairings first; the one whose completion explains most measurements wins.
inline constexpr int kTreeHypothesesVerified = 8;
// The same without a prior (relocalisation): against a whole map, coincidences with more tree pairings than
// the truth are common (the truth pairs only where the anchor's locality overlaps the scan), and with 8 kept
// the truth was crowded out in 4 of 50 kidnappings at n = 10^4 (uniform world, seed 1); 32 kept them.
inline constexpr int kTreeHypothesesVerifiedPoseFree = 32;
// Pose-free, the ranking above can still crowd out the truth: in 9 of 300 kidnappings at n = 10^4 (uniform
// world, seeds 1-6, 10 landmarks + 2 clutter per scan) 32 coincidences had more tree pairings than the
// truth's best anchor, and the winner explained 4-5 measurements where the truth explains 6-10. A winner
// that explains less than AssociationOptions::widen_below (0.5) of the scan, in a search the ranking cut
// short, therefore triggers a second search that keeps kTreeWideningFactor times as many verified
// hypotheses. Seeds 1-12 (600 kidnappings, with the re-pairing of complete()): factor 8: 585 relocalised,
// 64: 591, 512: 593 but 45 % more time in all; 64 costs about 3 %, since only ambiguous scans search twice.
inline constexpr int kTreeWideningFactor = 64;
// A hypothesis needs two pairings to fix a pose, so fewer are never accepted.
inline constexpr int kTreeMinPairings = 2;
// Early acceptance (TreeSettings::accept_explained) needs at least one measurement more than fixes the pose.
inline constexpr int kTreeMinAccepted = kTreeMinPairings + 1;

// Fills result. stats.hypotheses counts distinct pairing sets visited: 1 (the empty one) plus one per pairing
// node of the tree (a '*' branch changes no set). For the locality search this never exceeds
// n((c+1)^m - 1)/c + 1 (DESIGN.md §4), c = the largest locality among the candidates, per pass: a pose-free
// search that widens (kTreeWideningFactor) makes two passes and counts the nodes of both.
// pose (optional): the verified pose of the accepted hypothesis; *verified says whether there was one.
void solve_tree(const AssociationProblem& problem, const TreeSettings& settings, TreeScratch& scratch,
                AssociationResult& result, Pose2* pose = nullptr, bool* verified = nullptr);

// The DESIGN.md §4 bound n((c+1)^m - 1)/c + 1 (as a double: it overflows integers quickly).
double locality_hypothesis_bound(int n, int m, int c);

}  // namespace arbor::association

#endif  // ARBOR_VARIANTS_ASSOCIATION_TREE_SEARCH_H_
