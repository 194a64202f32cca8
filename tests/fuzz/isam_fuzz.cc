// libFuzzer target: the iSAM Victoria Park reader (experiments/loaders/isam_victoria_park.h), its conversion
// to a scenario, then the scenario writer.
#include "core/io/scenario_format.h"
#include "experiments/loaders/isam_victoria_park.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  fuzz::accepted([&] {
    const std::string path = fuzz::input_file(data, size, "input.isam");
    write_scenario(isam_to_scenario(read_isam_dataset(path), path), (fuzz::scratch_dir() / "out.scn").string());
  });
  return 0;
}
