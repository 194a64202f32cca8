// `arbor relocalize`: the kidnapped robot (DESIGN.md §4, issue 4 item 6). A robot in a known simulated map
// loses its pose: NN and JCBB are given a wrong prior (the pose before a large jump) and the map landmarks in
// range of that prior; the locality tree gets no prior and the whole map. Reports per strategy, over many
// trials, two success rates (every pairing right; the pose the pairings imply near the truth), hypotheses and
// time per call.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <random>
#include <string>
#include <numeric>
#include <vector>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/engine/rng.h"
#include "core/math/chi_square.h"
#include "core/io/field_limits.h"
#include "core/io/input_error.h"
#include "core/io/memory_budget.h"
#include "core/metrics/run_statistics.h"
#include "core/models/range_bearing_model.h"
#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"
#include "experiments/sim/simulator.h"
#include "experiments/sim/world.h"
#include "variants/association/association_common.h"
#include "variants/association/rigid_alignment.h"
#include "variants/association/strategy_list.h"

namespace arbor::cli {
namespace {

struct RelocalizeArgs {
  std::string world = "uniform";
  int landmarks = 1000;
  int observations = 10;
  double clutter = 2.0;
  int trials = 100;
  std::uint64_t seed = 1;
  double jump_m = 10.0;
  double jump_rad = 1.0;
  double map_sigma_m = 0.1;
  double accept = 0.0;
  double widen_below = AssociationOptions{}.widen_below;
  // Three standard deviations of the pose the filter's --relocalize re-seeds its particles around
  // (FastSlam::kRelocalizeSigma: 0.2 m, 0.03 rad): a pose inside them is one the filter recovers from.
  double pose_tolerance_m = 0.6;
  double pose_tolerance_rad = 0.09;
  std::vector<std::string> strategies{"nn", "jcbb", "locality"};
  bool csv = false;
};

// The known map: every landmark estimated to map_sigma, with its covisibility locality (the nearest
// landmarks within sensor range and in line of sight, capped: what a mapping run would have recorded).
struct KnownMap {
  std::vector<Vec2> mean;
  Mat2 cov;
  std::vector<LocalitySet> locality;
};

KnownMap make_known_map(const World& world, const SensorModel& sensor, const LandmarkGrid& grid, double sigma,
                        std::mt19937_64& rng) {
  KnownMap map;
  std::normal_distribution<double> normal(0.0, sigma);
  map.cov = Mat2::Identity() * sigma * sigma;
  const int n = static_cast<int>(world.landmarks.size());
  map.mean.resize(n);
  map.locality.resize(n);
  for (int j = 0; j < n; ++j) map.mean[j] = world.landmarks[j].position + draw_vec2([&] { return normal(rng); });
  std::vector<std::pair<double, int>> near;
  for (int j = 0; j < n; ++j) {
    const Vec2& p = world.landmarks[j].position;
    near.clear();
    grid.visit_within(p, sensor.max_range_m, [&](int h) {
      const Vec2& q = world.landmarks[h].position;
      const double d = (q - p).norm();
      if (h != j && d <= sensor.max_range_m && world.line_of_sight(p, q)) near.push_back({d, h});
    });
    std::sort(near.begin(), near.end());
    for (const auto& [d, h] : near) {
      if (map.locality[j].size() == LocalitySet::kCapacity) break;
      map.locality[j].add(h);
    }
  }
  return map;
}

AssociationCandidate make_candidate(const KnownMap& map, int j, const Pose2& prior, const Mat2& R) {
  AssociationCandidate c;
  c.id = j;
  Mat2 H;
  c.z_hat = range_bearing_predict(prior, map.mean[j], &H, &c.H_pose);
  c.S = H * map.cov * H.transpose() + R;
  c.position = map.mean[j];
  c.position_cov = map.cov;
  c.locality = map.locality[j];
  return c;
}

// The ceiling any strategy faces: gated nearest neighbour at the TRUE pose against the whole known map
// (`whole_map`, whose candidate j is landmark j), pairs taken by increasing Mahalanobis distance. It fails
// where the data are ambiguous whatever the search: a clutter point inside the gate of a mapped landmark the
// scan did not measure, or two landmarks closer than the map's noise whose estimates are nearer crosswise.
std::vector<LandmarkId> oracle_pairing(const AssociationProblem& whole_map, const Pose2& truth, const KnownMap& map,
                                       const LandmarkGrid& grid, double gate2) {
  const int m = static_cast<int>(whole_map.measurements.size());
  std::vector<association::GatedPair> pairs;
  for (int i = 0; i < m; ++i) {
    const Vec2& z = whole_map.measurements[i].z;
    const Vec2 w = range_bearing_inverse(truth, z);
    const Mat2 cov = range_bearing_initial_covariance(truth, z, whole_map.R) + map.cov;
    const Mat2 inverse = cov.inverse();
    // r^T C^-1 r <= gate2 implies |r| <= sqrt(gate2 * trace C); the metre covers the map's noise.
    grid.visit_within(w, std::sqrt(gate2 * cov.trace()) + 1.0, [&](int j) {
      const Vec2 r = w - map.mean[j];
      const double d2 = r.dot(inverse * r);
      if (d2 <= gate2) pairs.push_back({d2, i, j});
    });
  }
  std::vector<int> rank(m);
  std::iota(rank.begin(), rank.end(), 0);
  std::vector<char> taken(map.mean.size(), 0);
  std::vector<LandmarkId> pairing(m, association::kUnassigned);
  association::pair_greedily(whole_map, rank, &pairs, &taken, &pairing);
  return pairing;
}

// Relocalised: at least three correct pairings (enough to fix the pose) and no wrong one.
bool relocalised(const std::vector<LandmarkId>& pairing, const std::vector<LandmarkId>& truth_ids) {
  int correct = 0, wrong = 0;
  for (std::size_t i = 0; i < pairing.size(); ++i)
    if (pairing[i] >= 0) (pairing[i] == truth_ids[i] ? correct : wrong) += 1;
  return correct >= 3 && wrong == 0;
}

// The pose a pairing implies: the rigid fit of its measured points onto the paired landmarks' map estimates.
// Needs three pairings, as `relocalised` does; false with fewer.
bool implied_pose(const AssociationProblem& problem, const std::vector<LandmarkId>& pairing, const KnownMap& map,
                  Pose2* pose) {
  std::vector<Vec2> robot, world;
  for (std::size_t i = 0; i < pairing.size(); ++i) {
    if (pairing[i] < 0) continue;
    robot.push_back(range_bearing_inverse(Pose2{}, problem.measurements[i].z));
    world.push_back(map.mean[pairing[i]]);
  }
  return robot.size() >= 3 && association::align_rigid_2d(robot, world, pose);
}

// Both definitions of success for one answer: every pairing right (`relocalised`), and the pose it implies
// within the tolerance of the truth. The second is what a filter needs to be found again; the first also
// fails where a clutter point sits inside the gate of a landmark the scan did not measure, which no search
// can tell from a measurement of it.
struct Tally {
  int success = 0;
  int pose_success = 0;
  std::vector<double> seconds, hypotheses;
  std::vector<double> position_error_m;  // of the implied poses within the tolerance

  void add(const std::vector<LandmarkId>& pairing, const std::vector<LandmarkId>& truth_ids,
           const AssociationProblem& problem, const KnownMap& map, const Pose2& truth, const RelocalizeArgs& a) {
    success += relocalised(pairing, truth_ids);
    Pose2 pose;
    if (!implied_pose(problem, pairing, map, &pose)) return;
    const double error_m = (pose.position() - truth.position()).norm();
    if (error_m > a.pose_tolerance_m || std::abs(wrap_angle(pose.theta - truth.theta)) > a.pose_tolerance_rad) return;
    pose_success += 1;
    position_error_m.push_back(error_m);
  }
};

int run_relocalize(const RelocalizeArgs& a) {
  WorldOptions wo;
  if (!from_string(a.world, &wo.kind)) throw InputError("", 0, "--world", "must be uniform, clustered or rooms");
  if (a.landmarks < 3) throw InputError("", 0, "--landmarks", "must be at least 3");
  // 735 bytes a landmark at 10^6 (peak RSS 743 MB: the world, its grid and the known map's locality sets):
  // 2 * 10^9 ended in std::bad_alloc, with a hint about options relocalize does not have (hostile C6).
  require_memory(a.landmarks, 700.0, "--landmarks", "landmarks");
  if (a.observations < 2) throw InputError("", 0, "--observations", "must be at least 2");
  if (a.trials < 1) throw InputError("", 0, "--trials", "must be at least 1");
  for (const auto& s : a.strategies)
    if (!visit_strategy(s, []<class S>() {}))
      throw InputError("", 0, "--assoc", fmt::format("unknown strategy '{}' (valid: {})", s,
                                                     fmt::join(standalone_strategy_names(), ", ")));
  wo.landmarks = a.landmarks;
  wo.seed = a.seed;
  const World world = make_world(wo);
  // The simulator's sensor, so the relocalisation figures hold for the simulated runs' measurements.
  const SensorModel sensor = SimulationOptions::default_sensor();
  const Mat2 R = sensor.R();
  const LandmarkGrid grid(world, sensor.max_range_m);
  std::mt19937_64 rng(a.seed * 7919 + 17);
  const KnownMap map = make_known_map(world, sensor, grid, a.map_sigma_m, rng);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::normal_distribution<double> normal(0.0, 1.0);
  AssociationOptions options;
  options.accept_explained = a.accept;
  options.widen_below = a.widen_below;
  std::vector<Tally> tally(a.strategies.size());
  // Pose covariance the prior claims (odometry-sized), far smaller than the jump: the prior is confidently wrong.
  const Mat3 P = Vec3(0.5 * 0.5, 0.5 * 0.5, 0.1 * 0.1).asDiagonal();
  const double gate2 = chi_square_quantile(options.gate_probability, 2);
  Tally oracle;

  for (int trial = 0; trial < a.trials; ++trial) {
    // A pose with at least `observations` visible landmarks, away from the border.
    Pose2 truth;
    std::vector<std::pair<double, int>> visible;
    for (int attempt = 0; attempt < 100; ++attempt) {
      truth = {world.side_m * (0.1 + 0.8 * unit(rng)), world.side_m * (0.1 + 0.8 * unit(rng)),
               wrap_angle(kPi * (2.0 * unit(rng) - 1.0))};
      visible.clear();
      grid.visit_within(truth.position(), sensor.max_range_m, [&](int j) {
        const Vec2 z = range_bearing_predict(truth, world.landmarks[j].position);
        if (sensor.in_view(z) && world.line_of_sight(truth.position(), world.landmarks[j].position))
          visible.push_back({z.x(), j});
      });
      if (static_cast<int>(visible.size()) >= a.observations) break;
    }
    std::sort(visible.begin(), visible.end());
    visible.resize(std::min<std::size_t>(visible.size(), a.observations));
    AssociationProblem measured;
    std::vector<LandmarkId> truth_ids;
    for (const auto& [r, j] : visible) {
      Vec2 z = range_bearing_predict(truth, world.landmarks[j].position);
      z += Vec2(sensor.sigma_range_m, sensor.sigma_bearing_rad).cwiseProduct(draw_vec2([&] { return normal(rng); }));
      measured.measurements.push_back({Vec2(std::max(z.x(), 0.0), wrap_angle(z.y()))});
      truth_ids.push_back(j);
    }
    std::poisson_distribution<int> clutter(a.clutter);
    for (int k = clutter(rng); k > 0; --k) {
      const double r = sensor.min_range_m + (sensor.max_range_m - sensor.min_range_m) * unit(rng);
      measured.measurements.push_back({Vec2(r, 0.5 * sensor.fov_rad * (2.0 * unit(rng) - 1.0))});
      truth_ids.push_back(-1);
    }
    // The kidnapping: the prior is where the robot was before a jump of jump_m and jump_rad.
    const double dir = kPi * (2.0 * unit(rng) - 1.0);
    const Pose2 prior{truth.x + a.jump_m * std::cos(dir), truth.y + a.jump_m * std::sin(dir),
                      wrap_angle(truth.theta + (unit(rng) < 0.5 ? -1.0 : 1.0) * a.jump_rad)};
    AssociationProblem with_prior = measured, whole_map = measured;
    with_prior.R = whole_map.R = R;
    with_prior.P = P;
    grid.visit_within(prior.position(), sensor.max_range_m + 2.0, [&](int j) {
      const AssociationCandidate c = make_candidate(map, j, prior, R);
      if (c.z_hat.x() <= sensor.max_range_m + 2.0 && std::abs(c.z_hat.y()) <= 0.5 * sensor.fov_rad + 0.2)
        with_prior.candidates.push_back(c);
    });
    std::sort(with_prior.candidates.begin(), with_prior.candidates.end(),
              [](const auto& x, const auto& y) { return x.id < y.id; });
    for (int j = 0; j < static_cast<int>(map.mean.size()); ++j)
      whole_map.candidates.push_back(make_candidate(map, j, prior, R));

    for (std::size_t s = 0; s < a.strategies.size(); ++s) {
      visit_strategy(a.strategies[s], [&]<class S>() {
        const bool pose_free = S::kName == LocalityTree::kName || S::kName == InterpretationTree::kName;
        const AssociationProblem& problem = pose_free ? whole_map : with_prior;
        const S strategy(options);
        typename S::Scratch scratch;
        AssociationResult r;
        const auto start = std::chrono::steady_clock::now();
        if constexpr (requires(Pose2 pose) { strategy.solve_with_pose(problem, scratch, r, &pose); }) {
          Pose2 pose;  // the pose-free search, without the prior check that solve() applies per particle
          strategy.solve_with_pose(problem, scratch, r, &pose);
        } else {
          strategy.solve(problem, scratch, r);
        }
        tally[s].seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
        tally[s].hypotheses.push_back(static_cast<double>(r.stats.hypotheses));
        tally[s].add(r.pairing, truth_ids, problem, map, truth, a);
      });
    }
    oracle.add(oracle_pairing(whole_map, truth, map, grid, gate2), truth_ids, whole_map, map, truth, a);
  }
  const auto rate = [&](int count) { return static_cast<double>(count) / a.trials; };
  if (a.csv)
    fmt::print("strategy,world,n,m,clutter,trials,success_rate,median_hypotheses,median_time_s,p90_time_s,"
               "pose_success_rate,median_position_error_m\n");
  for (std::size_t s = 0; s < a.strategies.size(); ++s) {
    const Tally& t = tally[s];
    if (a.csv)
      fmt::print("{},{},{},{},{},{},{:.4f},{},{:.9g},{:.9g},{:.4f},{:.4g}\n", a.strategies[s], a.world, a.landmarks,
                 a.observations, a.clutter, a.trials, rate(t.success), median(t.hypotheses), median(t.seconds),
                 quantile(t.seconds, 0.9), rate(t.pose_success), median(t.position_error_m));
    else
      fmt::print("{:<10} n={} m={} clutter={} trials={} success={:.3f} pose_success={:.3f} median_position_error_m="
                 "{:.3f} median_hypotheses={} median_time_s={:.6f} p90_time_s={:.6f}\n",
                 a.strategies[s], a.landmarks, a.observations, a.clutter, a.trials, rate(t.success),
                 rate(t.pose_success), median(t.position_error_m), median(t.hypotheses), median(t.seconds),
                 quantile(t.seconds, 0.9));
  }
  // The ceiling: what pairing at the true pose achieves on the same trials (no search, so no time).
  if (a.csv)
    fmt::print("oracle,{},{},{},{},{},{:.4f},0,0,0,{:.4f},{:.4g}\n", a.world, a.landmarks, a.observations, a.clutter,
               a.trials, rate(oracle.success), rate(oracle.pose_success), median(oracle.position_error_m));
  else
    fmt::print("{:<10} n={} m={} clutter={} trials={} success={:.3f} pose_success={:.3f} median_position_error_m="
               "{:.3f} (gated NN at the true pose: the data's ceiling)\n",
               "oracle", a.landmarks, a.observations, a.clutter, a.trials, rate(oracle.success),
               rate(oracle.pose_success), median(oracle.position_error_m));
  return 0;
}

}  // namespace

void add_relocalize_command(CLI::App& app, CommandAction* action) {
  auto args = std::make_shared<RelocalizeArgs>();
  CLI::App* cmd = app.add_subcommand(
      "relocalize",
      "Kidnapped-robot experiment in a known simulated map: NN and JCBB get a wrong pose prior (the pose before a "
      "jump) and the landmarks in range of it; the locality tree gets no prior and the whole map. Success = at "
      "least three correct pairings and no wrong one; pose success = the pose the pairings imply within the tolerance "
      "of the truth. Prints both rates, median hypotheses and time per strategy.");
  cmd->add_option("--world", args->world, "uniform, clustered or rooms")->capture_default_str();
  cmd->add_option("--landmarks", args->landmarks, "Map size n")->capture_default_str();
  cmd->add_option("--observations", args->observations, "Measured landmarks per scan m (the nearest visible)")
      ->capture_default_str();
  // simulate's cap: each spurious measurement is drawn and searched, so 1e9 of them hung and exhausted memory.
  cmd->add_option("--clutter", args->clutter, "Expected spurious measurements per scan (Poisson)")
      ->check(within(0.0, kMaxClutterRate))
      ->capture_default_str();
  cmd->add_option("--trials", args->trials, "Kidnappings")->capture_default_str();
  cmd->add_option("--seed", args->seed, "Random seed (world and trials)")
      ->check(unsigned_number())
      ->capture_default_str();
  cmd->add_option("--jump-m", args->jump_m, "Position jump of the kidnapping [m]")->capture_default_str();
  cmd->add_option("--jump-rad", args->jump_rad, "Heading jump of the kidnapping [rad]")->capture_default_str();
  cmd->add_option("--map-sigma", args->map_sigma_m, "Std dev of the known map's landmark estimates [m]")
      ->check(within(0.0, scenario_limits::kMaxSigma))  // a scenario's sigma limit: its square must not overflow
      ->capture_default_str();
  cmd->add_option("--accept", args->accept,
                  "Pose-free search: stop at the first pose that explains this fraction of the scan (0: search to "
                  "the bound)")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--widen-below", args->widen_below,
                  "Pose-free search: search again, keeping more hypotheses, when the winner explains less than this "
                  "fraction of the scan (0: never)")
      ->check(within(0.0, 1.0))
      ->capture_default_str();
  cmd->add_option("--pose-tolerance-m", args->pose_tolerance_m,
                  "Pose success: the implied pose's position within this of the truth [m]")
      ->check(at_least(0.0))
      ->capture_default_str();
  cmd->add_option("--pose-tolerance-rad", args->pose_tolerance_rad,
                  "Pose success: the implied pose's heading within this of the truth [rad]")
      ->check(at_least(0.0))
      ->capture_default_str();
  cmd->add_option("--assoc", args->strategies, "Strategies to compare")->delimiter(',')->capture_default_str();
  cmd->add_flag("--csv", args->csv, "CSV output with a header line");
  cmd->callback([args, action] { *action = [args] { return run_relocalize(*args); }; });
}

}  // namespace arbor::cli
