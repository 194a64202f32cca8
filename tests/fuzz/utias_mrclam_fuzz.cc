// libFuzzer target: the UTIAS MRCLAM converter (experiments/loaders/utias_mrclam.h) on a copy of
// tests/data/utias_mrclam with one of its five files replaced by the input, the noise estimation of
// `convert --estimate-noise`, then the scenario writer.
#include "core/io/scenario_format.h"
#include "experiments/loaders/noise_estimation.h"
#include "experiments/loaders/utias_mrclam.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace arbor;
  static fuzz::DatasetCopy copy(ARBOR_SOURCE_DIR "/tests/data/utias_mrclam",
                                {"Barcodes.dat", "Landmark_Groundtruth.dat", "Robot1_Groundtruth.dat",
                                 "Robot1_Odometry.dat", "Robot1_Measurement.dat"});
  copy.with_input(data, size, [](const std::string& dir) {
    fuzz::accepted([&] {
      LoadReport report;
      Scenario scenario = load_utias_mrclam(dir, UtiasOptions{}, &report);
      apply_noise_estimates(estimate_measurement_noise(scenario), estimate_motion_noise(scenario, 1.0), &scenario);
      write_scenario(scenario, (fuzz::scratch_dir() / "out.scn").string());
    });
  });
  return 0;
}
