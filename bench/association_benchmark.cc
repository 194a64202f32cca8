// Association strategies on generated problems: time per call (median, p90), hypotheses, tests, F1 and the
// fraction of jointly compatible answers, vs m, n and clutter, the locality tree vs the unrestricted one, and
// the DESIGN.md §10 cases. Prints one CSV row per configuration (per-call distributions need a custom loop,
// not Google Benchmark's per-iteration means); analysis/studies/plot_association.py reads the CSV.
//   association_benchmark [--quick] [--group NAME] > results/association/<commit>_<host>_<compiler>/association.csv
#include <algorithm>
#include <chrono>
#include <cstring>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "core/io/build_info.h"
#include "core/metrics/run_statistics.h"
#include "variants/association/joint_compatibility.h"
#include "variants/association/problem_generator.h"
#include "variants/association/strategy_list.h"

namespace arbor {
namespace {

struct Case {
  std::string group;  // m | n | clutter | tree | design
  std::string strategy;
  int n, m, clutter, seeds;
  std::int64_t budget = 1'000'000;
};

void run_case(const Case& c) {
  std::vector<double> seconds, hypotheses, tests;
  AssociationCounts counts;
  int compatible = 0, exhausted = 0;
  AssociationOptions options;
  options.max_hypotheses = c.budget;
  visit_strategy(c.strategy, [&]<class S>() {
    const S strategy(options);
    typename S::Scratch scratch;
    for (int seed = 1; seed <= c.seeds; ++seed) {
      const ProblemGeneratorOptions g{
          .landmarks = c.n,
          .observations = c.m,
          .clutter = c.clutter,
          .seed = static_cast<std::uint64_t>(seed),
      };
      const GeneratedProblem gen = generate_association_problem(g);
      AssociationResult r;
      strategy.solve(gen.problem, scratch, r);  // warm the scratch buffers and caches
      const auto start = std::chrono::steady_clock::now();
      strategy.solve(gen.problem, scratch, r);
      seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
      hypotheses.push_back(static_cast<double>(r.stats.hypotheses));
      tests.push_back(static_cast<double>(r.stats.tests));
      exhausted += r.stats.budget_exhausted;
      counts += score_against_truth(r.pairing, gen.truth);
      compatible += association::joint_compatibility(gen.problem, r.pairing, options.gate_probability).compatible;
    }
  });
  const auto opt = [](std::optional<double> v) { return v ? fmt::format("{:.4f}", *v) : std::string("nan"); };
  double mean_h = 0.0;
  for (double h : hypotheses) mean_h += h / hypotheses.size();
  fmt::print("{},{},{},{},{},{},{:.9g},{:.9g},{:.9g},{:.6g},{:.6g},{:.6g},{},{},{},{:.4f},{:.4f}\n", c.group, c.strategy,
             c.n, c.m, c.clutter, c.seeds, quantile(seconds, 0.5), quantile(seconds, 0.9), quantile(seconds, 1.0),
             quantile(hypotheses, 0.5), mean_h, quantile(tests, 0.5), opt(counts.precision()), opt(counts.recall()),
             opt(counts.f1()), static_cast<double>(compatible) / c.seeds, static_cast<double>(exhausted) / c.seeds);
  std::fflush(stdout);
}

}  // namespace
}  // namespace arbor

int main(int argc, char** argv) {
  using arbor::Case;
  bool quick = false;
  std::string only_group;  // --group NAME runs one group (design, m, n, clutter, tree_n, tree_m)
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0) quick = true;
    if (std::strcmp(argv[i], "--group") == 0 && i + 1 < argc) only_group = argv[++i];
  }
  const int seeds = quick ? 5 : 50;
  std::vector<Case> cases;
  // DESIGN.md §10: n = 200, 20 + 5 and n = 500, 30 + 10.
  for (const char* s : {"nn", "nn-independent", "jcbb", "locality"}) {
    const int design_seeds = quick ? 10 : (std::string(s) == "locality" ? 40 : 200);
    cases.push_back({"design", s, 200, 20, 5, design_seeds});
    cases.push_back({"design", s, 500, 30, 10, design_seeds});
  }
  for (int m : {5, 10, 20, 30, 40})
    for (const char* s : {"nn", "jcbb", "locality"}) cases.push_back({"m", s, 200, m, m / 4, seeds});
  for (int n : {100, 300, 1000, 3000, 10000, 30000, 100000})
    for (const char* s : {"nn", "jcbb", "locality"})
      cases.push_back({"n", s, n, 10, 2, n >= 30000 ? 3 : (n >= 10000 ? std::min(seeds, 10) : seeds)});
  for (int clutter : {0, 5, 10, 20, 40})
    for (const char* s : {"nn", "jcbb"}) cases.push_back({"clutter", s, 200, 20, clutter, seeds});
  // Locality vs unrestricted: small m so that the unrestricted tree finishes; the budget caps it anyway.
  for (int n : {25, 50, 100, 200, 400})
    for (const char* s : {"locality", "itree"}) cases.push_back({"tree_n", s, n, 5, 1, quick ? 3 : 10, 2'000'000});
  for (int m : {3, 4, 5, 6, 7})
    for (const char* s : {"locality", "itree"}) cases.push_back({"tree_m", s, 100, m, 1, quick ? 3 : 10, 2'000'000});
  fmt::print("# commit={} host={} compiler={} build={}\n", arbor::git_commit(), arbor::host_name(), arbor::compiler(),
             arbor::build_type());
  fmt::print("group,strategy,n,m,clutter,seeds,median_s,p90_s,max_s,median_hypotheses,mean_hypotheses,"
             "median_tests,precision,recall,f1,jointly_compatible,budget_exhausted\n");
  for (const Case& c : cases)
    if (only_group.empty() || c.group == only_group) arbor::run_case(c);
  return 0;
}
