// FactorGraph -> g2o 2-D text (see g2o_writer.h).
#include "variants/smoothing/g2o_writer.h"

#include <cmath>
#include <iterator>

#include <Eigen/LU>
#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

// {:.17g} round-trips every double.
void append_information(std::string& out, const Mat3& covariance) {
  Mat3 info = covariance.inverse();
  info = 0.5 * (info + info.transpose());
  fmt::format_to(std::back_inserter(out), " {:.17g} {:.17g} {:.17g} {:.17g} {:.17g} {:.17g}", info(0, 0), info(0, 1),
                 info(0, 2), info(1, 1), info(1, 2), info(2, 2));
}

void append_information(std::string& out, const Mat2& covariance) {
  Mat2 info = covariance.inverse();
  info = 0.5 * (info + info.transpose());
  fmt::format_to(std::back_inserter(out), " {:.17g} {:.17g} {:.17g}", info(0, 0), info(0, 1), info(1, 1));
}

}  // namespace

void write_g2o(const FactorGraph& graph, const std::string& path) {
  std::string out;
  auto it = std::back_inserter(out);
  const int P = static_cast<int>(graph.poses.size());
  fmt::format_to(it, "# arbor factor graph: {} poses (ids 0..{}), {} landmarks (ids {}..{}), {} factors\n", P, P - 1,
                 graph.landmarks.size(), P, P + static_cast<int>(graph.landmarks.size()) - 1, graph.factor_count());
  for (int i = 0; i < P; ++i) {
    const Pose2& x = graph.poses[i].initial;
    fmt::format_to(it, "VERTEX_SE2 {} {:.17g} {:.17g} {:.17g}\n", i, x.x, x.y, x.theta);
  }
  for (std::size_t j = 0; j < graph.landmarks.size(); ++j) {
    const GraphLandmark& l = graph.landmarks[j];
    fmt::format_to(it, "# landmark id {}\nVERTEX_XY {} {:.17g} {:.17g}\n", l.id, P + j, l.initial.x(), l.initial.y());
  }
  for (const PosePriorFactor& f : graph.priors) fmt::format_to(it, "FIX {}\n", f.pose);
  for (const BetweenFactor& f : graph.betweens) {
    fmt::format_to(it, "EDGE_SE2 {} {} {:.17g} {:.17g} {:.17g}", f.from, f.to, f.delta.x, f.delta.y, f.delta.theta);
    append_information(out, f.covariance);
    out += '\n';
  }
  for (const PointFactor& f : graph.points) {
    fmt::format_to(it, "EDGE_SE2_XY {} {} {:.17g} {:.17g}", f.pose, P + f.landmark, f.p_robot.x(), f.p_robot.y());
    append_information(out, f.covariance);
    out += '\n';
  }
  for (const RangeBearingFactor& f : graph.range_bearings) {
    // The point at (r, phi) seen from the origin pose: range_bearing_inverse gives it and d point / d z.
    Mat2 J;
    const Vec2 p = range_bearing_inverse(Pose2{}, f.z, &J);
    fmt::format_to(it, "EDGE_SE2_XY {} {} {:.17g} {:.17g}", f.pose, P + f.landmark, p.x(), p.y());
    append_information(out, Mat2(J * f.covariance * J.transpose()));
    out += '\n';
  }
  write_file_atomically(path, out);
}

}  // namespace arbor
