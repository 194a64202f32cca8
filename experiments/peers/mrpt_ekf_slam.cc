// Peer cross-check (issue 43, item 6): MRPT 2.5's EKF-SLAM, mrpt::slam::CRangeBearingKFSLAM2D, run on an
// Arbor scenario with known association, so that `arbor run --filter ekf --assoc known` has an outside
// reference on the same problem. Writes DIR/trajectory.tum, DIR/timing.json (time per scan, landmarks),
// DIR/steps.csv (the same per scan, in `arbor run`'s columns) and DIR/accuracy.json, scored by Arbor's own
// metric code so that both filters are measured alike.
//
// Usage: mrpt_ekf_slam --scenario FILE --out DIR [--stock-start] [--davison]
//
// MRPT's default update (kfEKFNaive) forms K for all of a scan's measurements and P <- (I - K H) P as a dense
// n x n product: O(n^3) per scan, and not symmetric. --davison takes its other EKF update (kfEKFAlaDavison):
// one scalar measurement at a time, P <- P - K S K^T on the upper half, mirrored; O(n^2) per scalar.
//
// What is matched, and how: MRPT takes one pose increment per scan with a Gaussian covariance in the frame of
// the previous scan's pose. The increment and its covariance are Arbor's own motion model run from the
// identity through the steps since that scan (MotionModel::predict), so MRPT's prediction,
// F P F^T + R(theta) Q R(theta)^T, is the one Arbor's EKF makes up to where each linearises. The sensor noise
// is the scenario's sigma_range and sigma_bearing; each measurement carries its landmark's true id, which
// MRPT pairs by id and never runs its own association for. Clutter (no true id) is left out, as known
// association leaves it out in Arbor.
#include <mrpt/obs/CActionCollection.h>
#include <mrpt/obs/CActionRobotMovement2D.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/obs/CSensoryFrame.h>
#include <mrpt/poses/CPosePDFGaussian.h>
#include <mrpt/slam/CRangeBearingKFSLAM2D.h>

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <numeric>
#include <optional>
#include <Eigen/Cholesky>  // LDLT
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/io/scenario_format.h"
#include "core/io/trajectory_io.h"
#include "core/metrics/run_statistics.h"
#include "core/metrics/trajectory_metrics.h"

namespace {

using arbor::Mat3;
using arbor::Pose2;

// MRPT's filter, with two things it keeps protected set from outside: the start (MRPT always starts at the
// origin with zero covariance; Arbor starts at the scenario's initial pose and sigma), and the prediction
// before the first landmark. Stock MRPT skips the prediction, mean included, while the map is empty, which
// drops the motion up to the first scan; unless asked for the stock behaviour the pose is predicted then too,
// as Arbor does.
// A covariance with a negative LDL^T pivot beyond rounding; zero pivots pass.
template <typename M>
bool indefinite(const M& P) {
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(P);
  return ldlt.vectorD().minCoeff() < -1e-12 * std::max(1.0, ldlt.vectorD().cwiseAbs().maxCoeff());
}

class PeerFilter : public mrpt::slam::CRangeBearingKFSLAM2D {
 public:
  PeerFilter(const Pose2& start, const arbor::Vec3& sigma, bool stock_start) : stock_start_(stock_start) {
    m_xkk[0] = start.x;
    m_xkk[1] = start.y;
    m_xkk[2] = start.theta;
    for (int i = 0; i < 3; ++i) m_pkk(i, i) = sigma[i] * sigma[i];
  }

  Pose2 pose() const { return {m_xkk[0], m_xkk[1], m_xkk[2]}; }
  Mat3 pose_covariance() const { return m_pkk.asEigen().block<3, 3>(0, 0); }
  std::size_t landmarks() const { return getNumberOfLandmarksInTheMap(); }
  // Whether the joint covariance has a negative pivot: semidefinite is fine (an exactly known start pose).
  bool joint_covariance_indefinite() const { return indefinite(m_pkk.asEigen()); }
  // The map as Arbor's metric code reads it: each landmark labelled with the true id it was started from.
  std::vector<arbor::Landmark> map() const {
    std::vector<arbor::Landmark> out;
    for (const auto& [index, id] : m_IDs.getInverseMap()) {
      arbor::Landmark lm;
      lm.mean = {m_xkk[3 + 2 * index], m_xkk[3 + 2 * index + 1]};
      lm.truth_label = static_cast<std::int32_t>(id);
      out.push_back(lm);
    }
    return out;
  }

 protected:
  void OnTransitionModel(const KFArray_ACT& u, KFArray_VEH& xv, bool& skip) const override {
    CRangeBearingKFSLAM2D::OnTransitionModel(u, xv, skip);
    if (!skip || stock_start_) return;
    const mrpt::poses::CPose2D moved =
        mrpt::poses::CPose2D(xv[0], xv[1], xv[2]) + mrpt::poses::CPose2D(u[0], u[1], u[2]);
    xv[0] = moved.x();
    xv[1] = moved.y();
    xv[2] = moved.phi();
    skip = false;
  }

 private:
  bool stock_start_;
};

// One pose increment with its covariance in the start pose's frame, as MRPT's odometry action.
mrpt::obs::CActionCollection::Ptr odometry_action(const Pose2& delta, const Mat3& cov) {
  mrpt::obs::CActionRobotMovement2D move;
  move.estimationMethod = mrpt::obs::CActionRobotMovement2D::emOdometry;
  mrpt::math::CMatrixDouble33 c;
  c.asEigen() = 0.5 * (cov + cov.transpose());
  move.poseChange = mrpt::poses::CPosePDFGaussian::Create(mrpt::poses::CPose2D(delta.x, delta.y, delta.theta), c);
  auto actions = mrpt::obs::CActionCollection::Create();
  actions->insert(move);
  return actions;
}

// One scan as MRPT's range-bearing observation, every measurement with its true landmark id.
mrpt::obs::CSensoryFrame::Ptr scan_frame(const arbor::ScenarioStep& step, const arbor::SensorModel& sensor,
                                         int* clutter_dropped) {
  auto obs = mrpt::obs::CObservationBearingRange::Create();
  obs->minSensorDistance = static_cast<float>(sensor.min_range_m);
  obs->maxSensorDistance = static_cast<float>(sensor.max_range_m);
  obs->fieldOfView_yaw = static_cast<float>(sensor.fov_rad);
  obs->sensor_std_range = static_cast<float>(sensor.sigma_range_m);
  obs->sensor_std_yaw = static_cast<float>(sensor.sigma_bearing_rad);
  for (const arbor::Measurement& m : step.measurements) {
    if (m.truth_id < 0) {
      ++*clutter_dropped;
      continue;
    }
    // MRPT keeps range and bearing as float: rounding of about 1e-6 m and 1e-7 rad, far below the sensor's
    // noise, but the reason the two filters' figures part in the sixth digit.
    mrpt::obs::CObservationBearingRange::TMeasurement z;
    z.range = static_cast<float>(m.range_m);
    z.yaw = static_cast<float>(m.bearing_rad);
    z.pitch = 0.0f;
    z.landmarkID = m.truth_id;
    obs->sensedData.push_back(z);
  }
  auto frame = mrpt::obs::CSensoryFrame::Create();
  frame->insert(obs);
  return frame;
}

void write_json(const std::string& path, const nlohmann::json& j) {
  std::ofstream f(path);
  f << j.dump(2) << "\n";
  if (!f) throw std::runtime_error("cannot write " + path);
}

nlohmann::json number_or_null(const std::optional<double>& v) { return v ? nlohmann::json(*v) : nullptr; }

// A statistic of a sample, null for an empty one (as `arbor run` writes it).
template <typename F>
nlohmann::json statistic(const std::vector<double>& values, F f) {
  return values.empty() ? nlohmann::json(nullptr) : nlohmann::json(f(values));
}

int run(const std::string& scenario_path, const std::string& out_dir, bool stock_start, bool davison) {
  const arbor::Scenario scenario = arbor::read_scenario(scenario_path);
  PeerFilter filter(scenario.initial_pose, scenario.initial_sigma, stock_start);
  // The sensor noise, as MRPT takes it: a float option, not the observation's own figures.
  filter.options.std_sensor_range = static_cast<float>(scenario.sensor.sigma_range_m);
  filter.options.std_sensor_yaw = static_cast<float>(scenario.sensor.sigma_bearing_rad);
  filter.options.create_simplemap = false;
  filter.KF_options.method = davison ? mrpt::bayes::kfEKFAlaDavison : mrpt::bayes::kfEKFNaive;

  std::vector<arbor::TimedPose> trajectory{{scenario.start_time_s, scenario.initial_pose}};
  std::vector<double> scan_times, nees;
  std::string steps_csv = "step,time_s,step_time_s,landmarks\n";
  Pose2 delta;  // motion since the last scan, in that scan's pose frame
  Mat3 delta_cov = Mat3::Zero();
  double last_time = scenario.start_time_s;
  int clutter_dropped = 0;
  // The first scan after which MRPT's pose is not finite or its pose covariance is indefinite. Its
  // update, P - K S K^T without symmetrising, lets the joint covariance drift indefinite on long runs with
  // hundreds of landmarks, and then the filter blows up; the figures after that point are not the filter's.
  std::optional<double> diverged_at_s;
  // The first checked scan at which the whole joint covariance is indefinite: checked every
  // kDefiniteCheckScans scans (a Cholesky of the full matrix, untimed), since its first loss comes long before
  // the pose block shows it.
  constexpr int kDefiniteCheckScans = 20;
  std::optional<double> indefinite_at_s;
  for (const arbor::ScenarioStep& step : scenario.steps) {
    scenario.motion.predict(&delta, &delta_cov, step.control, step.time_s - last_time);
    last_time = step.time_s;
    if (step.has_scan) {
      auto actions = odometry_action(delta, delta_cov);
      auto frame = scan_frame(step, scenario.sensor, &clutter_dropped);
      // Only MRPT's own work is timed, not the building of its input objects.
      const auto t0 = std::chrono::steady_clock::now();
      filter.processActionObservation(actions, frame);
      scan_times.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      fmt::format_to(std::back_inserter(steps_csv), "{},{},{:.9f},{}\n", &step - scenario.steps.data(), step.time_s,
                     scan_times.back(), filter.landmarks());
      delta = Pose2{};
      delta_cov.setZero();
      const Mat3 P = filter.pose_covariance();
      if (!diverged_at_s && (!filter.pose().vector().allFinite() || !P.allFinite() || indefinite(P)))
        diverged_at_s = step.time_s;
      if (!indefinite_at_s && scan_times.size() % kDefiniteCheckScans == 0 && filter.joint_covariance_indefinite())
        indefinite_at_s = step.time_s;
      // As `arbor run` counts it: scans with a truth pose, and not at an exactly known pose (0/0); and only
      // until MRPT blows up.
      if (step.truth_pose && P.trace() > 1e-9 && !diverged_at_s)
        nees.push_back(arbor::pose_nees(filter.pose(), P, *step.truth_pose));
    }
    if (step.has_scan || step.truth_pose) trajectory.push_back({step.time_s, filter.pose().compose(delta)});
  }

  std::filesystem::create_directories(out_dir);
  arbor::write_tum(out_dir + "/trajectory.tum", trajectory);
  std::ofstream(out_dir + "/steps.csv") << steps_csv;
  write_json(out_dir + "/timing.json",
             {{"scans", scan_times.size()},
              {"step_time_median_s", statistic(scan_times, [](auto& v) { return arbor::quantile(v, 0.5); })},
              {"step_time_p95_s", statistic(scan_times, [](auto& v) { return arbor::quantile(v, 0.95); })},
              {"landmarks", filter.landmarks()},
              {"diverged_at_s", number_or_null(diverged_at_s)}});

  const auto truth = arbor::truth_positions(scenario);
  const auto ate = arbor::absolute_trajectory_error(trajectory, truth, false);
  const auto ate_aligned = arbor::absolute_trajectory_error(trajectory, truth, true);
  write_json(out_dir + "/accuracy.json",
             {{"ate_rmse_m", ate ? nlohmann::json(ate->rmse_m) : nullptr},
              {"ate_aligned_rmse_m", ate_aligned ? nlohmann::json(ate_aligned->rmse_m) : nullptr},
              {"landmark_rmse_m", number_or_null(arbor::landmark_rmse(filter.map(), scenario.truth_landmarks,
                                                                      ate ? ate->alignment : Pose2{}))},
              {"nees_mean",
               statistic(nees, [](auto& v) { return std::accumulate(v.begin(), v.end(), 0.0) / v.size(); })},
              {"nees_median", statistic(nees, [](auto& v) { return arbor::quantile(v, 0.5); })},
              {"nees_in_band_fraction",
               statistic(nees, [](auto& v) { return arbor::fraction_in_band(v, arbor::kNeesBand3Dof95); })},
              {"diverged_at_s", number_or_null(diverged_at_s)},
              {"joint_covariance_indefinite_at_s", number_or_null(indefinite_at_s)},
              {"clutter_dropped", clutter_dropped},
              {"stock_start", stock_start},
              {"kf_method", davison ? "kfEKFAlaDavison" : "kfEKFNaive"},
              {"scenario", scenario_path}});
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  std::string scenario, out;
  bool stock_start = false, davison = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--scenario" && i + 1 < argc) scenario = argv[++i];
    else if (arg == "--out" && i + 1 < argc) out = argv[++i];
    else if (arg == "--stock-start") stock_start = true;
    else if (arg == "--davison") davison = true;
    else {
      std::fprintf(stderr, "unknown argument '%s'\n", arg.c_str());
      scenario.clear();
      break;
    }
  }
  if (scenario.empty() || out.empty()) {
    std::fprintf(stderr, "usage: mrpt_ekf_slam --scenario FILE --out DIR [--stock-start] [--davison]\n");
    return 2;
  }
  try {
    return run(scenario, out, stock_start, davison);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mrpt_ekf_slam: %s\n", e.what());
    return 1;
  }
}
