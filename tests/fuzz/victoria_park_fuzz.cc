// libFuzzer target: the Victoria Park converter (experiments/loaders/victoria_park.h) on a copy of
// tests/data/victoria_park with one of its three files replaced by the input, then the scenario writer.
#include "experiments/loaders/victoria_park.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  static fuzz::DatasetCopy copy(ARBOR_SOURCE_DIR "/tests/data/victoria_park",
                                {"csv_from_mat/aa3_dr.csv", "csv_from_mat/aa3_gpsx.csv", "leung_extracted/measurements.dat"});
  fuzz::convert_and_write(copy, data, size, [](const std::string& dir) {
    LoadReport report;
    return load_victoria_park(dir, &report);
  });
  return 0;
}
