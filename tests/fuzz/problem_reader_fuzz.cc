// libFuzzer target: the association-problem reader (DESIGN.md §4), then every standalone strategy on
// whatever it accepts, with a small search budget. Properties: no crash, no sanitizer report, no hang, and
// every answer pairs each observation with a candidate or with nothing.
#include <cstdlib>

#include "tests/fuzz/fuzz_support.h"
#include "variants/association/problem_generator.h"
#include "variants/association/problem_io.h"
#include "variants/association/strategy_list.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  AssociationProblem problem;
  if (!fuzz::accepted([&] { problem = read_association_problem(fuzz::input_file(data, size, "input.problem")); }))
    return 0;
  AssociationOptions options;
  options.max_hypotheses = 2000;
  assign_nearest_localities(&problem, options.locality_capacity);
  for (const std::string& name : standalone_strategy_names()) {
    visit_strategy(name, [&]<class S>() {
      const S strategy(options);
      typename S::Scratch scratch;
      AssociationResult result;
      strategy.solve(problem, scratch, result);
      if (result.pairing.size() != problem.measurements.size()) std::abort();
    });
  }
  return 0;
}
