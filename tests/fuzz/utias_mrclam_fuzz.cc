// libFuzzer target: the UTIAS MRCLAM converter (experiments/loaders/utias_mrclam.h) on a copy of
// tests/data/utias_mrclam with one of its five files replaced by the input, the noise estimation of
// `convert --estimate-noise`, then the scenario writer.
#include "experiments/loaders/noise_estimation.h"
#include "experiments/loaders/utias_mrclam.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  static fuzz::DatasetCopy copy(ARBOR_SOURCE_DIR "/tests/data/utias_mrclam",
                                {"Barcodes.dat", "Landmark_Groundtruth.dat", "Robot1_Groundtruth.dat",
                                 "Robot1_Odometry.dat", "Robot1_Measurement.dat"});
  fuzz::convert_and_write(copy, data, size, [](const std::string& dir) {
    LoadReport report;
    Scenario scenario = load_utias_mrclam(dir, UtiasOptions{}, &report);
    apply_noise_estimates(estimate_measurement_noise(scenario), estimate_motion_noise(scenario, 1.0), &scenario);
    return scenario;
  });
  return 0;
}
