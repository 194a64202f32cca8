// Export of a factor graph in g2o's 2-D text format, so g2o, GTSAM (readG2o) and others solve the same
// problem as Arbor's smoother.
#ifndef ARBOR_VARIANTS_SMOOTHING_G2O_WRITER_H_
#define ARBOR_VARIANTS_SMOOTHING_G2O_WRITER_H_

#include <string>

#include "variants/smoothing/factor_graph.h"

namespace arbor {

// Vertices carry the graph's initial values: VERTEX_SE2 (poses, ids 0..P-1) and VERTEX_XY (landmarks, ids
// P..P+L-1; a comment line maps them back to landmark ids). Edges carry information matrices (upper
// triangle, row major): EDGE_SE2 for between factors (same error convention as g2o's EdgeSE2), EDGE_SE2_XY
// for point factors and for range-bearing factors, which g2o's core 2-D types cannot express: z = (r, phi)
// becomes the point r (cos phi, sin phi) with covariance J R J^T (first order, exact at the measurement).
// Priors become "FIX" lines: a single prior only fixes the gauge, so its optimum equals the fixed one.
// Written atomically; throws InputError when the file cannot be written.
void write_g2o(const FactorGraph& graph, const std::string& path);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_SMOOTHING_G2O_WRITER_H_
