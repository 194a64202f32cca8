// One smoother run to its result files (DESIGN.md §9, `arbor smooth`): DIR/result.json (the fields of
// `arbor run` plus solve_time_s, iterations, initial_cost, final_cost, termination), DIR/trajectory.tum and
// DIR/map.csv; optionally the problem as a g2o file.
#ifndef ARBOR_EXPERIMENTS_RUN_SMOOTH_RUN_H_
#define ARBOR_EXPERIMENTS_RUN_SMOOTH_RUN_H_

#ifdef ARBOR_HAVE_SMOOTHER

#include <string>

#include <nlohmann/json.hpp>

#include "core/types/scenario.h"
#include "variants/smoothing/smoother.h"

namespace arbor {

struct SmoothConfig {
  std::string scenario_path;       // a scenario file, or
  std::string isam_path;           // a pre-associated iSAM/GTSAM file (then no scenario)
  std::string associations = "known";  // "known" (ground-truth ids) or a FastSLAM result directory
  // Initial values: "auto" (the FastSLAM run the associations come from, else dead reckoning),
  // "dead-reckoning", or a FastSLAM result directory (trajectory.tum; map.csv too when it is also the
  // association source).
  std::string init = "auto";
  // Robust loss on the landmark observations: "auto" (the default) is Cauchy on real data and none on
  // simulated data, whose noise is Gaussian by construction; or a SmootherLoss name (none, huber, cauchy).
  // Without a robust loss one robot per MRCLAM dataset lands 3.7-3.9 m off (issue 41).
  std::string loss = "auto";
  std::string g2o_path;            // optional: export the problem
  SmootherOptions options;
  std::string out_dir;             // empty: compute but write nothing
};

struct SmoothOutput {
  nlohmann::json result;
  SmootherResult smoother;
};

// Throws InputError for unreadable inputs and for associations that do not fit the scenario.
SmoothOutput run_smoother(const SmoothConfig& config);

// Association decisions of a FastSLAM result directory: DIR/associations.csv with the header
// "step,measurement,landmark" and one row per measurement (the landmark the best particle updated or
// created; -1: judged spurious, left out), plus the best particle's map (DIR/map.csv) for the landmarks'
// truth labels. Measurements without a row are left out. A landmark the particle later pruned still ties
// the poses that saw it together; it has no truth label.
SmootherAssociations read_association_decisions(const std::string& dir, const Scenario& scenario);

}  // namespace arbor

#endif  // ARBOR_HAVE_SMOOTHER
#endif  // ARBOR_EXPERIMENTS_RUN_SMOOTH_RUN_H_
