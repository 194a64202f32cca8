// The iSAM/GTSAM 2-D text format -> FactorGraph (see isam_graph.h).
#include "variants/smoothing/isam_graph.h"

#include <algorithm>
#include <deque>
#include <map>
#include <set>

#include <Eigen/Cholesky>
#include <fmt/core.h>

#include "core/io/input_error.h"
#include "core/io/text_reader.h"

namespace arbor {
namespace {

struct RawOdometry {
  std::int64_t from, to;
  Pose2 delta;
  Mat3 covariance;
};
struct RawLandmark {
  std::int64_t pose, landmark;
  Vec2 p_robot;
  Mat2 covariance;
};

template <int N>
void require_positive_definite(const TextReader& in, const Eigen::Matrix<double, N, N>& covariance) {
  Eigen::LLT<Eigen::Matrix<double, N, N>> llt(covariance);
  if (llt.info() != Eigen::Success) in.fail("covariance", "covariance is not positive definite");
}

}  // namespace

FactorGraph read_isam_graph(const std::string& path, double prior_sigma) {
  TextReader in(path);
  std::vector<RawOdometry> odometry;
  std::vector<RawLandmark> sightings;
  std::map<std::int64_t, int> pose_line, landmark_line;  // id -> first line using it, for error messages
  const auto note_pose = [&](std::int64_t id, const char* field) {
    if (landmark_line.count(id))
      in.fail(field, fmt::format("id {} is a landmark (line {}) and cannot be a pose", id, landmark_line[id]));
    pose_line.try_emplace(id, in.line_number());
  };
  while (in.next()) {
    const std::string_view kind = in.field(0);
    if (kind == "ODOMETRY") {
      in.expect_fields(12, 12, "ODOMETRY");
      RawOdometry o;
      o.from = in.integer(1, "pose i");
      o.to = in.integer(2, "pose j");
      note_pose(o.from, "pose i");
      note_pose(o.to, "pose j");
      if (o.from == o.to) in.fail("pose j", "odometry from a pose to itself");
      o.delta = Pose2::from_vector(Vec3(in.number(3, "dx"), in.number(4, "dy"), in.number(5, "dtheta")));
      const double c[6] = {in.number(6, "c_xx"), in.number(7, "c_xy"), in.number(8, "c_xt"),
                           in.number(9, "c_yy"), in.number(10, "c_yt"), in.number(11, "c_tt")};
      o.covariance << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
      require_positive_definite<3>(in, o.covariance);
      odometry.push_back(o);
    } else if (kind == "LANDMARK") {
      in.expect_fields(8, 8, "LANDMARK");
      RawLandmark l;
      l.pose = in.integer(1, "pose i");
      l.landmark = in.integer(2, "landmark l");
      note_pose(l.pose, "pose i");
      if (pose_line.count(l.landmark))
        in.fail("landmark l", fmt::format("id {} is a pose (line {}) and cannot be a landmark", l.landmark,
                                          pose_line[l.landmark]));
      landmark_line.try_emplace(l.landmark, in.line_number());
      l.p_robot = Vec2(in.number(3, "x"), in.number(4, "y"));
      const double c[3] = {in.number(5, "c_xx"), in.number(6, "c_xy"), in.number(7, "c_yy")};
      l.covariance << c[0], c[1], c[1], c[2];
      require_positive_definite<2>(in, l.covariance);
      sightings.push_back(l);
    } else {
      in.fail("type", fmt::format("unknown line type '{}' (expected ODOMETRY or LANDMARK)", kind));
    }
  }
  if (pose_line.empty()) throw InputError(path, 0, "", "no ODOMETRY or LANDMARK lines");

  FactorGraph graph;
  std::map<std::int64_t, int> pose_index;
  for (const auto& [id, line] : pose_line) {
    pose_index[id] = static_cast<int>(graph.poses.size());
    graph.poses.push_back({static_cast<double>(graph.poses.size()), -1, id, Pose2{}});
  }
  for (const RawOdometry& o : odometry)
    graph.betweens.push_back({pose_index[o.from], pose_index[o.to], o.delta, o.covariance});

  // Dead reckoning: breadth first over the odometry from the lowest id, composing (or inverting) deltas.
  std::vector<std::vector<int>> incident(graph.poses.size());
  for (int f = 0; f < static_cast<int>(graph.betweens.size()); ++f) {
    incident[graph.betweens[f].from].push_back(f);
    incident[graph.betweens[f].to].push_back(f);
  }
  std::vector<bool> reached(graph.poses.size(), false);
  reached[0] = true;
  std::deque<int> queue{0};
  while (!queue.empty()) {
    const int i = queue.front();
    queue.pop_front();
    for (int f : incident[i]) {
      const BetweenFactor& b = graph.betweens[f];
      const int other = b.from == i ? b.to : b.from;
      if (reached[other]) continue;
      const Pose2& here = graph.poses[i].initial;
      graph.poses[other].initial =
          b.from == i ? here.compose(b.delta) : here.compose(b.delta.between(Pose2{}));  // delta^-1
      reached[other] = true;
      queue.push_back(other);
    }
  }
  for (std::size_t i = 0; i < reached.size(); ++i) {
    if (!reached[i])
      throw InputError(path, pose_line[graph.poses[i].source_id], "pose i",
                       fmt::format("pose {} is not connected to pose {} by odometry", graph.poses[i].source_id,
                                   graph.poses[0].source_id));
  }

  std::map<std::int64_t, int> landmark_index;
  for (const RawLandmark& l : sightings) {
    const int pose = pose_index[l.pose];
    auto [it, inserted] = landmark_index.try_emplace(l.landmark, static_cast<int>(graph.landmarks.size()));
    if (inserted) graph.landmarks.push_back({l.landmark, graph.poses[pose].initial.transform(l.p_robot)});
    graph.points.push_back({pose, it->second, l.p_robot, l.covariance});
  }
  PosePriorFactor prior;
  prior.pose = 0;
  prior.mean = Pose2{};
  prior.covariance = Mat3::Identity() * prior_sigma * prior_sigma;
  graph.priors.push_back(prior);
  return graph;
}

}  // namespace arbor
