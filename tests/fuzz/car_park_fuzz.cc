// libFuzzer target: the ACFR Car Park converter (experiments/loaders/acfr_car_park.h) on a copy of
// tests/data/acfr_car_park with one of its five files replaced by the input, the noise estimation of
// `convert --estimate-noise`, then the scenario writer.
#include "experiments/loaders/acfr_car_park.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  static fuzz::DatasetCopy copy(ARBOR_SOURCE_DIR "/tests/data/acfr_car_park",
                                {"csv/dead_reckoning.csv", "csv/gps.csv", "csv/beacons_groundtruth.csv",
                                 "csv/laser_ranges.csv", "csv/laser_intensity.csv"});
  fuzz::convert_and_write(copy, data, size, [](const std::string& dir) {
    LoadReport report;
    Scenario scenario = load_acfr_car_park(dir, &report);
    apply_noise_estimate(estimate_car_park_noise(scenario), &scenario);
    return scenario;
  });
  return 0;
}
