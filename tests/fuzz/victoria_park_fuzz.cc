// libFuzzer target: the Victoria Park converter (experiments/loaders/victoria_park.h) on a copy of
// tests/data/victoria_park with one of its three files replaced by the input, then the scenario writer.
#include "core/io/scenario_format.h"
#include "experiments/loaders/victoria_park.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  static fuzz::DatasetCopy copy(ARBOR_SOURCE_DIR "/tests/data/victoria_park",
                                {"csv_from_mat/aa3_dr.csv", "csv_from_mat/aa3_gpsx.csv", "leung_extracted/measurements.dat"});
  copy.with_input(data, size, [](const std::string& dir) {
    fuzz::accepted([&] {
      LoadReport report;
      write_scenario(load_victoria_park(dir, &report), (fuzz::scratch_dir() / "out.scn").string());
    });
  });
  return 0;
}
