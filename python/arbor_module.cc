// The compiled half of `import arbor` (python/arbor/__init__.py is the other): scenarios, the run pipeline
// and the step-by-step filter on numpy arrays. Options arrive as `--name=value` strings and are parsed by the
// same definitions as the command line (experiments/options/), so names, defaults, checks and results are the
// CLI's. Arrays cross once, copied into numpy-owned memory (one copy; nothing aliases the engine's state).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <chrono>
#include <cctype>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/engine/filter.h"
#include "core/engine/numerical_breakdown.h"
#include "core/io/build_info.h"
#include "core/io/field_limits.h"
#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "experiments/options/run_options.h"
#include "experiments/options/simulation_options.h"
#include "experiments/run/fastslam_run.h"
#include "experiments/sim/simulator.h"
#include "variants/filter_list.h"
#include "variants/registry.h"

namespace py = pybind11;

namespace arbor::python {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Arguments = std::vector<std::string>;

// A rows x cols array filled by row(i, out) with cols doubles.
template <class Fill>
Array table(std::size_t rows, std::size_t cols, Fill&& row) {
  Array a({rows, cols});
  double* data = a.mutable_data();
  for (std::size_t i = 0; i < rows; ++i) row(i, data + i * cols);
  return a;
}

Array poses_array(const std::vector<TimedPose>& poses) {
  return table(poses.size(), 4, [&](std::size_t i, double* r) {
    r[0] = poses[i].time_s, r[1] = poses[i].pose.x, r[2] = poses[i].pose.y, r[3] = poses[i].pose.theta;
  });
}

// The map as a dict of arrays: id (K), mean (K x 2), covariance (K x 2 x 2), log_odds, confirmed.
py::dict map_dict(const std::vector<Landmark>& map) {
  const std::size_t k = map.size();
  py::array_t<std::int32_t> ids(k);
  py::array_t<bool> confirmed(k);
  Array log_odds(k), cov({k, std::size_t{2}, std::size_t{2}});
  for (std::size_t i = 0; i < k; ++i) {
    ids.mutable_at(i) = map[i].id;
    confirmed.mutable_at(i) = map[i].confirmed;
    log_odds.mutable_at(i) = map[i].log_odds;
    for (int r = 0; r < 2; ++r)
      for (int c = 0; c < 2; ++c) cov.mutable_at(i, r, c) = map[i].cov(r, c);
  }
  py::dict d;
  d["id"] = ids;
  d["mean"] = table(k, 2, [&](std::size_t i, double* r) { r[0] = map[i].mean.x(), r[1] = map[i].mean.y(); });
  d["covariance"] = cov;
  d["log_odds"] = log_odds;
  d["confirmed"] = confirmed;
  return d;
}

// Ctrl-C during a long call: the GIL is released, so Python's handler only sets a flag; look at it every
// 50 ms (one acquisition, microseconds) and end the run with KeyboardInterrupt.
std::function<void()> interrupt_check() {
  return [last = std::chrono::steady_clock::now()]() mutable {
    const auto now = std::chrono::steady_clock::now();
    if (now - last < std::chrono::milliseconds(50)) return;
    last = now;
    py::gil_scoped_acquire gil;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  };
}

// ---- Scenario ----------------------------------------------------------------------------------------------

[[noreturn]] void array_error(const std::string& field, const std::string& message) {
  throw InputError("Scenario.from_arrays", 0, field, message);
}

// The checks of the scenario reader (docs/scenario_format.md, "Limits"), for arrays: `source` names the call
// (Scenario.from_arrays, Filter.step) and `field` the array and element.
void check_within(double v, double lo, double hi, const std::string& field, const char* source = "Scenario.from_arrays") {
  if (!(v >= lo && v <= hi)) throw InputError(source, 0, field, fmt::format("{} is outside [{}, {}]", v, lo, hi));
}
// A bearing within [-pi, pi] (as the reader allows, up to rounding), returned wrapped.
double checked_bearing(double v, const std::string& field, const char* source = "Scenario.from_arrays") {
  check_within(v, -kPi - 1e-9, kPi + 1e-9, field, source);
  return wrap_angle(v);
}
// A landmark id given as a number: an integer within [lo, kMaxLandmarkId] (NaN and 1.5 are not ids).
std::int32_t checked_id(double v, std::int32_t lo, const std::string& field) {
  check_within(v, lo, scenario_limits::kMaxLandmarkId, field);
  if (v != std::floor(v)) array_error(field, fmt::format("{} is not an integer id", v));
  return static_cast<std::int32_t>(v);
}

// Builds a scenario from the user's own arrays, checked against the limits of docs/scenario_format.md; each
// error names the array and the element. The models and the initial pose come from `like` (a scenario with
// the right motion and sensor models, e.g. a converted dataset or a simulation), overridden by `sensor`.
Scenario scenario_from_arrays(const Scenario& like, Array times, Array controls, py::object scans,
                              py::object measurements, py::object truth_poses, py::object truth_landmarks,
                              py::dict metadata) {
  namespace lim = scenario_limits;
  Scenario s;
  s.motion = like.motion;
  s.sensor = like.sensor;
  s.initial_pose = like.initial_pose;
  s.initial_sigma = like.initial_sigma;
  s.start_time_s = like.start_time_s;
  for (auto [k, v] : metadata) s.metadata[py::str(k)] = py::str(v);
  if (times.ndim() != 1) array_error("times", "must be one-dimensional (T)");
  const std::size_t t = times.shape(0);
  if (controls.ndim() != 2 || controls.shape(0) != static_cast<py::ssize_t>(t) || controls.shape(1) != 3)
    array_error("controls", fmt::format("must have shape ({}, 3)", t));
  s.steps.resize(t);
  double last = s.start_time_s;
  for (std::size_t k = 0; k < t; ++k) {
    ScenarioStep& step = s.steps[k];
    step.time_s = times.at(k);
    check_within(step.time_s, -lim::kMaxTime, lim::kMaxTime, fmt::format("times[{}]", k));
    if (step.time_s < last) array_error(fmt::format("times[{}]", k), "times must not go backwards");
    last = step.time_s;
    for (int j = 0; j < 3; ++j) {
      step.control[j] = controls.at(k, j);
      check_within(step.control[j], -lim::kMaxControl, lim::kMaxControl, fmt::format("controls[{}, {}]", k, j));
    }
  }
  if (!truth_poses.is_none()) {
    const Array truth = truth_poses.cast<Array>();
    if (truth.ndim() != 2 || truth.shape(0) != static_cast<py::ssize_t>(t) || truth.shape(1) != 3)
      array_error("truth_poses", fmt::format("must have shape ({}, 3); a row of NaN means no truth there", t));
    for (std::size_t k = 0; k < t; ++k) {
      if (std::isnan(truth.at(k, 0))) continue;
      for (int j = 0; j < 3; ++j)
        check_within(truth.at(k, j), -lim::kMaxCoordinate, lim::kMaxCoordinate, fmt::format("truth_poses[{}, {}]", k, j));
      s.steps[k].truth_pose = Pose2{truth.at(k, 0), truth.at(k, 1), truth.at(k, 2)};
    }
  }
  if (!measurements.is_none()) {
    const py::dict z = measurements.cast<py::dict>();
    for (const char* key : {"step", "range", "bearing"})
      if (!z.contains(key)) array_error("measurements", fmt::format("needs the arrays 'step', 'range' and 'bearing'"));
    const auto steps = z["step"].cast<py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>>();
    const auto range = z["range"].cast<Array>(), bearing = z["bearing"].cast<Array>();
    const std::size_t n = steps.size();
    if (range.size() != static_cast<py::ssize_t>(n) || bearing.size() != static_cast<py::ssize_t>(n))
      array_error("measurements", "'step', 'range' and 'bearing' must have the same length");
    Array truth_ids;
    if (z.contains("truth_id")) {
      truth_ids = z["truth_id"].cast<Array>();  // as doubles, so that NaN and 1.5 are seen, not cast to ints
      if (truth_ids.size() != static_cast<py::ssize_t>(n)) array_error("measurements['truth_id']", "must have one id per measurement");
    }
    for (std::size_t i = 0; i < n; ++i) {
      const std::int64_t k = steps.at(i);
      if (k < 0 || k >= static_cast<std::int64_t>(t))
        array_error(fmt::format("measurements['step'][{}]", i), fmt::format("step {} is not in [0, {})", k, t));
      Measurement m;
      m.range_m = range.at(i);
      m.bearing_rad = bearing.at(i);
      check_within(m.range_m, 0.0, lim::kMaxRange, fmt::format("measurements['range'][{}]", i));
      m.bearing_rad = checked_bearing(m.bearing_rad, fmt::format("measurements['bearing'][{}]", i));
      // -2: unknown (real data), -1: clutter, else the true landmark's id.
      if (truth_ids.size() > 0) m.truth_id = checked_id(truth_ids.at(i), kTruthUnknown, fmt::format("measurements['truth_id'][{}]", i));
      ScenarioStep& step = s.steps[k];
      step.has_scan = true;
      step.measurements.push_back(m);
      if (step.measurements.size() > static_cast<std::size_t>(lim::kMaxMeasurementsPerScan))
        array_error(fmt::format("measurements['step'][{}]", i),
                    fmt::format("more than {} measurements at step {}", lim::kMaxMeasurementsPerScan, k));
    }
  }
  if (!scans.is_none()) {  // scans without measurements still give negative evidence
    const auto has_scan = scans.cast<py::array_t<bool, py::array::c_style | py::array::forcecast>>();
    if (has_scan.size() != static_cast<py::ssize_t>(t)) array_error("scans", fmt::format("must have length {}", t));
    for (std::size_t k = 0; k < t; ++k) {
      if (!has_scan.at(k) && !s.steps[k].measurements.empty())
        array_error(fmt::format("scans[{}]", k), "is False but the step has measurements");
      s.steps[k].has_scan = has_scan.at(k);
    }
  }
  if (!truth_landmarks.is_none()) {
    const Array lm = truth_landmarks.cast<Array>();
    if (lm.ndim() != 2 || lm.shape(1) != 3) array_error("truth_landmarks", "must have shape (L, 3): id, x, y");
    for (py::ssize_t i = 0; i < lm.shape(0); ++i) {
      for (int j = 1; j < 3; ++j)
        check_within(lm.at(i, j), -lim::kMaxCoordinate, lim::kMaxCoordinate, fmt::format("truth_landmarks[{}, {}]", i, j));
      const std::int32_t id = checked_id(lm.at(i, 0), 0, fmt::format("truth_landmarks[{}, 0]", i));
      for (const auto& other : s.truth_landmarks)
        if (other.id == id) array_error(fmt::format("truth_landmarks[{}, 0]", i), fmt::format("landmark {} is listed twice", id));
      s.truth_landmarks.push_back({id, {lm.at(i, 1), lm.at(i, 2)}});
    }
  }
  return s;
}

py::dict measurements_dict(const Scenario& s) {
  std::vector<std::int64_t> step;
  std::vector<double> range, bearing;
  std::vector<std::int32_t> truth;
  for (std::size_t k = 0; k < s.steps.size(); ++k)
    for (const Measurement& m : s.steps[k].measurements) {
      step.push_back(static_cast<std::int64_t>(k));
      range.push_back(m.range_m);
      bearing.push_back(m.bearing_rad);
      truth.push_back(m.truth_id);
    }
  py::dict d;
  d["step"] = py::array(py::cast(step));
  d["range"] = py::array(py::cast(range));
  d["bearing"] = py::array(py::cast(bearing));
  d["truth_id"] = py::array(py::cast(truth));
  return d;
}

py::dict sensor_dict(const SensorModel& z) {
  py::dict d;
  d["max_range"] = z.max_range_m;
  d["min_range"] = z.min_range_m;
  d["fov"] = z.fov_rad;
  d["sigma_range"] = z.sigma_range_m;
  d["sigma_bearing"] = z.sigma_bearing_rad;
  d["sigma_signature"] = z.sigma_signature;
  return d;
}

void bind_scenario(py::module_& m) {
  py::class_<Scenario, std::shared_ptr<Scenario>>(m, "Scenario",
      "A scenario: controls, scans and (where known) ground truth, as `arbor simulate` and `arbor convert` write "
      "them (docs/scenario_format.md).")
      .def_static("load", [](const std::filesystem::path& path) {
            py::gil_scoped_release release;
            return std::make_shared<Scenario>(read_scenario(path.string()));
          }, py::arg("path"), "Reads a scenario file; arbor.InputError names file, line and field.")
      .def("save", [](const Scenario& s, const std::filesystem::path& path) {
            py::gil_scoped_release release;
            write_scenario(s, path.string());
          }, py::arg("path"))
      .def_static("_from_arrays", [](const Scenario& like, Array times, Array controls, py::object scans,
                                     py::object measurements, py::object truth_poses, py::object truth_landmarks,
                                     py::dict metadata) {
            return std::make_shared<Scenario>(scenario_from_arrays(like, times, controls, scans, measurements,
                                                                   truth_poses, truth_landmarks, metadata));
          })
      .def("__len__", [](const Scenario& s) { return s.steps.size(); })
      .def_property_readonly("times", [](const Scenario& s) {
            return table(s.steps.size(), 1, [&](std::size_t i, double* r) { r[0] = s.steps[i].time_s; }).reshape({s.steps.size()});
          })
      .def_property_readonly("controls", [](const Scenario& s) {
            return table(s.steps.size(), 3, [&](std::size_t i, double* r) {
              for (int j = 0; j < 3; ++j) r[j] = s.steps[i].control[j];
            });
          })
      .def_property_readonly("scans", [](const Scenario& s) {
            py::array_t<bool> a(s.steps.size());
            for (std::size_t i = 0; i < s.steps.size(); ++i) a.mutable_at(i) = s.steps[i].has_scan;
            return a;
          }, "Whether each step ends with a scan (a scan may hold no measurement)")
      .def_property_readonly("truth_poses", [](const Scenario& s) {
            return table(s.steps.size(), 3, [&](std::size_t i, double* r) {
              const auto& p = s.steps[i].truth_pose;
              r[0] = p ? p->x : NAN, r[1] = p ? p->y : NAN, r[2] = p ? p->theta : NAN;
            });
          }, "T x 3 (x, y, theta); NaN rows where no truth is known")
      .def_property_readonly("measurements", &measurements_dict,
                             "A dict of arrays, one entry per measurement: step, range, bearing, truth_id "
                             "(-1 clutter, -2 unknown)")
      .def_property_readonly("truth_landmarks", [](const Scenario& s) {
            const auto& l = s.truth_landmarks;
            return table(l.size(), 3, [&](std::size_t i, double* r) {
              r[0] = l[i].id, r[1] = l[i].position.x(), r[2] = l[i].position.y();
            });
          })
      .def_property_readonly("gps", [](const Scenario& s) {
            const auto& g = s.truth_track;
            return table(g.size(), 3, [&](std::size_t i, double* r) {
              r[0] = g[i].time_s, r[1] = g[i].position.x(), r[2] = g[i].position.y();
            });
          })
      .def_property_readonly("metadata", [](const Scenario& s) { return s.metadata; })
      .def_property_readonly("sensor", [](const Scenario& s) { return sensor_dict(s.sensor); })
      .def_property_readonly("motion", [](const Scenario& s) { return std::string(to_string(s.motion.kind)); })
      .def_property_readonly("initial_pose", [](const Scenario& s) {
            return std::vector<double>{s.initial_pose.x, s.initial_pose.y, s.initial_pose.theta};
          })
      .def_property_readonly("start_time", [](const Scenario& s) { return s.start_time_s; });

  m.def("_simulate", [](const Arguments& arguments) {
        const SimulationOptions options = cli::simulation_options_from_arguments(arguments);
        py::gil_scoped_release release;
        return std::make_shared<Scenario>(simulate(options));
      });
}

// ---- A run and its result ----------------------------------------------------------------------------------

void bind_run(py::module_& m) {
  py::class_<RunOutput, std::shared_ptr<RunOutput>>(m, "_RunOutput")
      .def_property_readonly("result_json", [](const RunOutput& o) { return o.result.dump(); })
      .def_property_readonly("trajectory", [](const RunOutput& o) { return poses_array(o.trajectory); })
      .def_property_readonly("best_trajectory", [](const RunOutput& o) { return poses_array(o.best_trajectory); })
      .def_property_readonly("trajectory_mean", [](const RunOutput& o) { return poses_array(o.mean_trajectory); })
      .def_property_readonly("map", [](const RunOutput& o) { return map_dict(o.map); })
      .def_property_readonly("steps", [](const RunOutput& o) {
            const auto& s = o.steps;
            py::array_t<bool> resampled(s.size()), scan(s.size());
            py::array_t<std::int64_t> landmarks(s.size()), hypotheses(s.size());
            for (std::size_t i = 0; i < s.size(); ++i) {
              resampled.mutable_at(i) = s[i].stats.resampled;
              scan.mutable_at(i) = s[i].scan;
              landmarks.mutable_at(i) = static_cast<std::int64_t>(s[i].stats.best_landmarks);
              hypotheses.mutable_at(i) = s[i].stats.hypotheses;
            }
            const auto column = [&](auto get) {
              return table(s.size(), 1, [&](std::size_t i, double* r) { r[0] = get(s[i]); }).reshape({s.size()});
            };
            py::dict d;
            d["time_s"] = column([](const StepRecord& r) { return r.time_s; });
            d["step_time_s"] = column([](const StepRecord& r) { return r.step_time_s; });
            d["n_eff"] = column([](const StepRecord& r) { return r.stats.n_eff; });
            d["resampled"] = resampled;
            d["landmarks"] = landmarks;
            d["hypotheses"] = hypotheses;
            d["nees"] = column([](const StepRecord& r) { return r.nees.value_or(NAN); });
            d["scan"] = scan;
            if (o.lineage_recorded) d["ancestor_age_s"] = column([](const StepRecord& r) { return r.ancestor_age_s.value_or(NAN); });
            return d;
          })
      .def("to_dir", [](const RunOutput& o, const std::filesystem::path& dir) {
            py::gil_scoped_release release;
            write_run_files(o, dir.string());
          }, py::arg("path"));

  m.def("_run", [](const Scenario& scenario, const Arguments& arguments) {
        RunConfig config = cli::run_config_from_arguments(arguments);
        config.after_step = interrupt_check();
        py::gil_scoped_release release;
        return std::make_shared<RunOutput>(run_fastslam(scenario, config));
      });
}

// ---- The step-by-step filter -------------------------------------------------------------------------------

class PyFilter {
 public:
  PyFilter(const Scenario& header, const Arguments& arguments)
      : config_(cli::run_config_from_arguments(arguments)),
        filter_(make_run_filter(header, config_)) {}  // with its prior map, as arbor.run

  void step(double time_s, const Array& control, const Array& ranges, const Array& bearings, bool scan,
            const py::object& truth_pose) {
    // The same limits as a scenario file and Scenario.from_arrays: a NaN control made every pose NaN.
    namespace lim = scenario_limits;
    constexpr const char* kSource = "Filter.step";
    ScenarioStep s;
    check_within(time_s, -lim::kMaxTime, lim::kMaxTime, "time", kSource);
    s.time_s = time_s;
    if (control.size() != 3) throw InputError(kSource, 0, "control", "needs three values");
    for (int j = 0; j < 3; ++j) {
      check_within(control.at(j), -lim::kMaxControl, lim::kMaxControl, fmt::format("control[{}]", j), kSource);
      s.control[j] = control.at(j);
    }
    if (ranges.size() != bearings.size()) throw InputError(kSource, 0, "bearings", "needs as many bearings as ranges");
    if (ranges.size() > lim::kMaxMeasurementsPerScan)
      throw InputError(kSource, 0, "ranges", fmt::format("more than {} measurements in one scan", lim::kMaxMeasurementsPerScan));
    for (py::ssize_t i = 0; i < ranges.size(); ++i) {
      Measurement m;
      check_within(ranges.at(i), 0.0, lim::kMaxRange, fmt::format("ranges[{}]", i), kSource);
      m.range_m = ranges.at(i);
      m.bearing_rad = checked_bearing(bearings.at(i), fmt::format("bearings[{}]", i), kSource);
      s.measurements.push_back(m);
    }
    s.has_scan = scan || !s.measurements.empty();
    if (!truth_pose.is_none()) {
      const auto p = truth_pose.cast<std::vector<double>>();
      if (p.size() != 3) throw InputError(kSource, 0, "truth_pose", "needs three values (x, y, heading)");
      for (int j = 0; j < 2; ++j)
        check_within(p[j], -lim::kMaxCoordinate, lim::kMaxCoordinate, fmt::format("truth_pose[{}]", j), kSource);
      check_within(p[2], -lim::kMaxControl, lim::kMaxControl, "truth_pose[2]", kSource);
      s.truth_pose = Pose2{p[0], p[1], wrap_angle(p[2])};
    }
    if (time_s < last_time_s_) throw InputError("Filter.step", 0, "time", "times must not go backwards");
    last_time_s_ = time_s;
    try {
      py::gil_scoped_release release;
      filter_->step(s);
    } catch (const NumericalBreakdown& e) {
      // As `arbor run` reports it (experiments/run/fastslam_run.cc): the caller's figures are the cause.
      throw InputError("Filter.step", 0, "step",
                       fmt::format("the filter's arithmetic broke down: {}; the motion noise or controls are too large "
                                   "for it", e.what()));
    }
  }

  py::tuple particles() const {
    const std::vector<WeightedPose> p = filter_->particles();
    Array weights(p.size());
    for (std::size_t i = 0; i < p.size(); ++i) weights.mutable_at(i) = p[i].weight;
    return py::make_tuple(table(p.size(), 3, [&](std::size_t i, double* r) {
                            r[0] = p[i].pose.x, r[1] = p[i].pose.y, r[2] = p[i].pose.theta;
                          }),
                          weights);
  }

  py::tuple estimate() const {
    const PoseEstimate e = filter_->estimate();
    Array mean(3), cov({3, 3});
    for (int i = 0; i < 3; ++i) {
      mean.mutable_at(i) = e.mean.vector()[i];
      for (int j = 0; j < 3; ++j) cov.mutable_at(i, j) = e.covariance(i, j);
    }
    return py::make_tuple(mean, cov);
  }

  py::dict last_step() const {
    const StepStats& s = filter_->last_step_stats();
    py::dict d;
    d["n_eff"] = s.n_eff;
    d["resampled"] = s.resampled;
    d["hypotheses"] = s.hypotheses;
    d["budget_exhausted"] = s.budget_exhausted;
    d["landmarks"] = s.best_landmarks;
    d["relocalized"] = s.relocalized;
    return d;
  }

  const Filter& filter() const { return *filter_; }

 private:
  RunConfig config_;
  std::unique_ptr<Filter> filter_;
  double last_time_s_ = -INFINITY;
};

void bind_filter(py::module_& m) {
  py::class_<PyFilter>(m, "_Filter")
      .def(py::init<const Scenario&, const Arguments&>())
      .def("step", &PyFilter::step, py::arg("time"), py::arg("control"), py::arg("ranges"), py::arg("bearings"),
           py::arg("scan"), py::arg("truth_pose"))
      .def("particles", &PyFilter::particles)
      .def("estimate", &PyFilter::estimate)
      .def("last_step", &PyFilter::last_step)
      .def("best_map", [](const PyFilter& f) { return map_dict(f.filter().best_map()); })
      .def("best_trajectory", [](const PyFilter& f) { return poses_array(f.filter().best_trajectory()); })
      .def("path_mean_trajectory", [](const PyFilter& f) { return poses_array(f.filter().path_mean_trajectory()); });
}

// ---- What the typed API is made from ----------------------------------------------------------------------

// The run options' descriptors (experiments/options/run_options.cc) as dicts: the package builds arbor.run's
// signature and docs from them, and scripts/generate_python_stub.py the stub.
py::list run_options() {
  py::list out;
  for (const cli::RunOptionInfo& o : cli::run_option_info()) {
    py::dict d;
    d["name"] = o.name;
    d["help"] = o.help;
    d["type"] = o.type;
    d["default"] = o.default_text;
    d["choices"] = o.choices;
    d["required"] = o.required;
    out.append(d);
  }
  return out;
}

// PEP 440: the project's version (CMakeLists.txt) with the build's commit as its local label, e.g.
// 0.1+g2b1f81d, or 0.1+g2b1f81d.dirty when the tree had uncommitted changes.
std::string version() {
  std::string commit = git_commit();
  const bool dirty = commit.ends_with('+');
  if (dirty) commit.pop_back();
  for (char c : commit)
    if (!std::isxdigit(static_cast<unsigned char>(c))) return ARBOR_VERSION;  // "unknown": no label
  if (commit.empty()) return ARBOR_VERSION;
  return fmt::format("{}+g{}{}", ARBOR_VERSION, commit, dirty ? ".dirty" : "");
}

}  // namespace
}  // namespace arbor::python

PYBIND11_MODULE(_arbor, m) {
  using namespace arbor::python;
  m.doc() = "Arbor's engine; use it through the arbor package (python/arbor/__init__.py).";
  static py::exception<arbor::InputError> input_error(m, "InputError", PyExc_ValueError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const arbor::InputError& e) {
      // The message, and the file, line and field it names, as attributes. The message may quote the bad
      // input itself, bytes that are not UTF-8 among them (a 0xFF in a scenario file raised UnicodeDecodeError
      // instead of this error): they are shown as U+FFFD.
      const auto text = [](const std::string& s) {
        return py::reinterpret_steal<py::str>(PyUnicode_DecodeUTF8(s.data(), static_cast<Py_ssize_t>(s.size()), "replace"));
      };
      py::object error = py::handle(input_error.ptr())(text(e.what()));
      error.attr("file") = text(e.file());
      error.attr("line") = e.line();
      error.attr("field") = text(e.field());
      PyErr_SetObject(input_error.ptr(), error.ptr());
    }
  });
  m.def("map_backends", &arbor::map_backend_names, "The map back ends, as --map names them");
  m.def("association_strategies", &arbor::association_names, "The association strategies usable in the filter");
  m.def("filters", &arbor::online_filter_names, "The filters arbor.run and arbor.Filter run (variants/filter_list.h)");
  m.def("_run_options", &run_options, "The run options' descriptors, in `arbor run --help`'s order");
  m.attr("__version__") = version();
  bind_scenario(m);
  bind_run(m);
  bind_filter(m);
}
