// `arbor associate`: solves one association problem in the DESIGN.md §4 exchange format with a chosen
// strategy and prints the pairing per observation and its statistics; `--generate` writes a random problem
// with its ground truth, so Arbor can be compared with other libraries on identical problems.
#include <chrono>
#include <cmath>
#include <string>

#include <fmt/core.h>
#include <fmt/ranges.h>

#include "core/io/field_limits.h"
#include "core/io/input_error.h"
#include "core/metrics/association_score.h"
#include "experiments/cli/commands.h"
#include "experiments/options/option_checks.h"
#include "variants/association/joint_compatibility.h"
#include "core/metrics/association_score.h"
#include "variants/association/problem_generator.h"
#include "variants/association/problem_io.h"
#include "variants/association/strategy_list.h"

namespace arbor::cli {
namespace {

struct AssociateArgs {
  std::string problem;
  std::string assoc = "jcbb";
  double chi2 = 0.99;
  double new_landmark_chi2 = 0.999;
  std::int64_t max_hypotheses = AssociationOptions{}.max_hypotheses;
  std::int64_t max_work = AssociationOptions{}.max_work;
  std::string truth;
  bool generate = false;
  ProblemGeneratorOptions gen;
  std::vector<double> pose_sigma{0.3, 0.3, 0.05};
  std::string out;
};

int run_generate(const AssociateArgs& a) {
  if (a.out.empty()) throw InputError("", 0, "--out", "--generate needs --out FILE");
  ProblemGeneratorOptions g = a.gen;
  if (g.landmarks < 1) throw InputError("", 0, "--landmarks", "must be at least 1");
  if (g.observations < 0 || g.observations > g.landmarks)
    throw InputError("", 0, "--observations", fmt::format("must be in [0, landmarks = {}]", g.landmarks));
  if (g.clutter < 0) throw InputError("", 0, "--clutter", "must be >= 0");
  if (g.landmarks > 5000)
    throw InputError("", 0, "--landmarks", "the exchange format holds a dense 2N x 2N covariance: keep N <= 5000");
  if (a.pose_sigma.size() != 3) throw InputError("", 0, "--pose-sigma", "needs three values: x y theta");
  g.pose_sigma = Vec3(a.pose_sigma[0], a.pose_sigma[1], a.pose_sigma[2]);
  const GeneratedProblem gen = generate_association_problem(g);
  write_association_problem(a.out, gen.problem);
  write_association_truth(a.out + ".truth", gen.truth);
  fmt::print("wrote {} ({} observations, {} predictions) and {}.truth\n", a.out, gen.problem.measurements.size(),
             gen.problem.candidates.size(), a.out);
  return 0;
}

int run_solve(const AssociateArgs& a) {
  if (a.problem.empty()) throw InputError("", 0, "--problem", "needs --problem FILE (or --generate)");
  if (!(a.chi2 > 0.0 && a.chi2 < 1.0)) throw InputError("", 0, "--chi2", "must be a probability in (0, 1)");
  AssociationProblem problem = read_association_problem(a.problem);
  std::vector<LandmarkId> truth;
  if (!a.truth.empty()) truth = read_association_truth(a.truth, static_cast<int>(problem.measurements.size()));
  AssociationOptions options;
  options.gate_probability = a.chi2;
  options.new_landmark_probability = std::max(a.new_landmark_chi2, a.chi2);
  options.max_hypotheses = a.max_hypotheses;
  options.max_work = a.max_work;
  // The format carries no covisibility: the locality of a prediction is its nearest predicted neighbours.
  if (a.assoc == "locality") assign_nearest_localities(&problem, options.locality_capacity);
  AssociationResult result;
  double seconds = 0.0;
  const bool known = visit_strategy(a.assoc, [&]<class S>() {
    const S strategy(options);
    typename S::Scratch scratch;
    const auto start = std::chrono::steady_clock::now();
    strategy.solve(problem, scratch, result);
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  });
  if (!known)
    throw InputError("", 0, "--assoc", fmt::format("unknown strategy '{}' (valid: {})", a.assoc,
                                                   fmt::join(standalone_strategy_names(), ", ")));
  for (LandmarkId id : result.pairing) fmt::print("{}\n", id >= 0 ? id : -1);
  fmt::print("stats hypotheses={} tests={} seconds={:.9f}{}\n", result.stats.hypotheses, result.stats.tests, seconds,
             result.stats.budget_exhausted ? " budget_exhausted=1" : "");
  if (!truth.empty()) {
    const AssociationCounts c = score_against_truth(result.pairing, truth);
    const auto joint = association::joint_compatibility(problem, result.pairing, a.chi2);
    const auto show = [](std::optional<double> v) { return v ? fmt::format("{:.4f}", *v) : std::string("nan"); };
    fmt::print("score precision={} recall={} f1={} jointly_compatible={}\n", show(c.precision()), show(c.recall()),
               show(c.f1()), joint.compatible ? 1 : 0);
  }
  return 0;
}

}  // namespace

void add_associate_command(CLI::App& app, CommandAction* action) {
  auto args = std::make_shared<AssociateArgs>();
  CLI::App* cmd = app.add_subcommand(
      "associate",
      "Solve a data-association problem in the exchange format of DESIGN.md §4 and print, per observation, the "
      "paired landmark id (-1: unpaired), then 'stats hypotheses=H tests=T seconds=S'. With --generate, write a "
      "random problem and its ground truth (FILE.truth) instead.");
  cmd->add_option("--problem", args->problem, "Problem file (exchange format)");
  cmd->add_option("--assoc", args->assoc, fmt::format("Strategy: {}", fmt::join(standalone_strategy_names(), ", ")))
      ->capture_default_str();
  cmd->add_option("--chi2", args->chi2, "Gate probability of the chi-square tests (individual and joint)")
      ->check(open_probability())
      ->capture_default_str();
  cmd->add_option("--new-landmark-chi2", args->new_landmark_chi2,
                  "An unpaired observation outside this gate of every prediction is NEW, else SPURIOUS")
      ->check(open_probability())
      ->capture_default_str();
  cmd->add_option("--max-hypotheses", args->max_hypotheses, "Search budget of JCBB and the interpretation trees")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--max-work", args->max_work,
                  "Their work budget, in multiply-adds and candidate scans (a tree's compatibility test counts 16)")
      ->check(at_least(1))
      ->capture_default_str();
  cmd->add_option("--truth", args->truth, "Ground-truth file (one id or -1 per observation): also print a score line");
  cmd->add_flag("--generate", args->generate, "Write a random problem with known pairings to --out");
  cmd->add_option("--landmarks", args->gen.landmarks, "Generator: landmarks N (all are predictions)")->capture_default_str();
  cmd->add_option("--observations", args->gen.observations, "Generator: true observations M")->capture_default_str();
  cmd->add_option("--clutter", args->gen.clutter, "Generator: spurious observations")->capture_default_str();
  cmd->add_option("--seed", args->gen.seed, "Generator: random seed")
      ->check(unsigned_number())
      ->capture_default_str();
  // The generator's figures within the scenario limits (core/io/field_limits.h), so that it writes no problem
  // its own reader refuses: density 0 made every coordinate NaN, a sigma of 1e300 an infinite covariance.
  namespace lim = scenario_limits;
  cmd->add_option("--density", args->gen.density, "Generator: landmarks per m^2")
      ->check(within(1e-6, 1e6))  // the world's side sqrt(N / density) within [1 mm, 71 km]
      ->capture_default_str();
  cmd->add_option("--range-sigma", args->gen.range_sigma, "Generator: range noise [m]")
      ->check(within(lim::kMinSigmaRange, lim::kMaxSigma))
      ->capture_default_str();
  cmd->add_option("--bearing-sigma", args->gen.bearing_sigma, "Generator: bearing noise [rad]")
      ->check(within(lim::kMinSigmaBearing, lim::kMaxSigma))
      ->capture_default_str();
  cmd->add_option("--pose-sigma", args->pose_sigma, "Generator: pose prior std devs x [m] y [m] theta [rad]")
      ->expected(3)
      ->check(within(0.0, lim::kMaxSigma))
      ->capture_default_str();
  cmd->add_option("--out", args->out, "Generator: output problem file (truth goes to FILE.truth)");
  cmd->callback([args, action] { *action = [args] { return args->generate ? run_generate(*args) : run_solve(*args); }; });
}

}  // namespace arbor::cli
