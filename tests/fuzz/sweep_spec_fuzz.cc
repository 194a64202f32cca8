// libFuzzer target: the sweep spec reader (TOML, experiments/sweeps/README.md). Properties: no crash, no
// sanitizer report, and no grid past the reader's size guard.
#include "experiments/sweep/sweep_spec.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  arbor::fuzz::accepted([&] { arbor::read_sweep_spec(arbor::fuzz::input_file(data, size, "input.toml")); });
  return 0;
}
