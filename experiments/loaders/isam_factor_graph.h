// The pre-associated iSAM/GTSAM file (experiments/loaders/isam_victoria_park.h) as the smoother's factor
// graph: its odometry as relative-pose factors and its landmark sightings as Cartesian point factors, exactly
// as stated in the file, so `arbor smooth --isam` solves the problem other tools solve.
#ifndef ARBOR_EXPERIMENTS_LOADERS_ISAM_FACTOR_GRAPH_H_
#define ARBOR_EXPERIMENTS_LOADERS_ISAM_FACTOR_GRAPH_H_

#ifdef ARBOR_HAVE_SMOOTHER

#include <string>

#include "experiments/loaders/isam_victoria_park.h"
#include "variants/smoothing/factor_graph.h"

namespace arbor {

// Poses in chain order (GraphPose::source_id keeps the file's id; time_s is the pose's index, the file has
// no times), landmarks in order of first sighting, factors in file order. Initial values: the odometry
// composed from the first pose at the origin, each landmark from its first sighting. A prior with standard
// deviation prior_sigma (m, m, rad) holds the first pose at the origin and fixes the gauge.
FactorGraph isam_factor_graph(const IsamDataset& dataset, double prior_sigma = 1e-6);

// read_isam_dataset then isam_factor_graph; errors name the file, line and field.
inline FactorGraph read_isam_factor_graph(const std::string& path, double prior_sigma = 1e-6) {
  return isam_factor_graph(read_isam_dataset(path), prior_sigma);
}

}  // namespace arbor

#endif  // ARBOR_HAVE_SMOOTHER
#endif  // ARBOR_EXPERIMENTS_LOADERS_ISAM_FACTOR_GRAPH_H_
