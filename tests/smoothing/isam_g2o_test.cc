// The iSAM/GTSAM file as a factor graph (errors name file, line and field; a small graph solves to its truth) and the
// g2o export (one line per variable and factor, information = inverse covariance).
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include "core/io/input_error.h"
#include "variants/smoothing/g2o_writer.h"
#include "experiments/loaders/isam_factor_graph.h"
#include "variants/smoothing/smoother.h"

namespace arbor {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("arbor_smoothing_" + std::to_string(::getpid()) + "_" + name)).string();
}

std::string write_temp(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

// Three poses (ids 0, 2, 3: id 1 is a landmark) on a straight line, 1 m apart, and landmark 1 at (1, 1)
// seen from all three. Noise-free, so the solution is the truth.
const char* kSmallIsam =
    "ODOMETRY 0 2 1 0 0 0.01 0 0 0.01 0 0.001\n"
    "LANDMARK 0 1 1 1 0.04 0 0.04\n"
    "ODOMETRY 2 3 1 0 0 0.01 0 0 0.01 0 0.001\n"
    "LANDMARK 2 1 0 1 0.04 0 0.04\n"
    "LANDMARK 3 1 -1 1 0.04 0 0.04\n";

TEST(IsamGraph, ReadsPosesLandmarksAndFactors) {
  const FactorGraph g = read_isam_factor_graph(write_temp("small.txt", kSmallIsam));
  ASSERT_EQ(g.poses.size(), 3u);
  EXPECT_EQ(g.poses[1].source_id, 2);
  ASSERT_EQ(g.landmarks.size(), 1u);
  EXPECT_EQ(g.landmarks[0].id, 1);
  EXPECT_EQ(g.betweens.size(), 2u);
  EXPECT_EQ(g.points.size(), 3u);
  EXPECT_EQ(g.priors.size(), 1u);
  EXPECT_NEAR(g.poses[2].initial.x, 2.0, 1e-12);
  EXPECT_NEAR(g.betweens[0].covariance(2, 2), 0.001, 1e-15);
  const SmootherResult r = solve_factor_graph(g, SmootherOptions{});
  ASSERT_TRUE(r.summary.usable);
  EXPECT_NEAR(r.summary.final_cost, 0.0, 1e-12);
  EXPECT_NEAR(r.landmarks[0].position.x(), 1.0, 1e-6);
  EXPECT_NEAR(r.landmarks[0].position.y(), 1.0, 1e-6);
}

void expect_input_error(const std::string& text, int line, const std::string& field) {
  const std::string path = write_temp("bad.txt", text);
  try {
    read_isam_factor_graph(path);
    FAIL() << "no error for:\n" << text;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
  }
}

// The reader is the data loader's (experiments/loaders/isam_victoria_park.h); through the adapter its errors
// still name the file, line and field.
TEST(IsamGraph, MalformedInputNamesLineAndField) {
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0\n", 1, "#12");                     // truncated
  expect_input_error("ODOMETRY 0 1 1 x 0 0.01 0 0 0.01 0 0.001\n", 1, "dy");                  // not a number
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\nLANDMARK 1 0 1 1 1 0 1\n", 2, "l");  // a pose id
  expect_input_error("LANDMARK 0 5 1 1 1 0 1\n", 1, "i");                                    // pose not reached
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 -1\n", 1, "c_tt");                 // a negative variance
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0.02 0 0.01 0 0.001\n", 1, "c_xx");             // not SPD
  // Outside the limits of docs/scenario_format.md: the smoother inverts these (diag(1e300, 1e300) aborted it).
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\nLANDMARK 1 2 1 1 1e300 0 1e300\n", 2, "c_xx");
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\nLANDMARK 1 2 1e200 1 1 0 1\n", 2, "x");
  expect_input_error("ODOMETRY 0 1 1 0 0 1e-300 0 0 0.01 0 0.001\n", 1, "c_xx");
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\nEDGE2 0 1\n", 2, "type");
  expect_input_error("ODOMETRY 0 1 1 0 0 0.01 0 0 0.01 0 0.001\nODOMETRY 2 3 1 0 0 0.01 0 0 0.01 0 0.001\n", 2,
                     "i");  // 2 and 3 are not connected to 0
}

TEST(G2oWriter, OneLinePerVariableAndFactorWithInverseCovariances) {
  const FactorGraph g = read_isam_factor_graph(write_temp("small2.txt", kSmallIsam));
  const std::string path = temp_path("small.g2o");
  write_g2o(g, path);
  std::ifstream in(path);
  std::string line;
  int vertices_se2 = 0, vertices_xy = 0, edges_se2 = 0, edges_xy = 0, fixed = 0;
  while (std::getline(in, line)) {
    std::istringstream fields(line);
    std::string tag;
    fields >> tag;
    if (tag == "VERTEX_SE2") ++vertices_se2;
    if (tag == "VERTEX_XY") ++vertices_xy;
    if (tag == "FIX") ++fixed;
    if (tag == "EDGE_SE2") {
      ++edges_se2;
      int i, j;
      double dx, dy, dth, info[6];
      fields >> i >> j >> dx >> dy >> dth;
      for (double& v : info) fields >> v;
      EXPECT_NEAR(info[0], 100.0, 1e-9);
      EXPECT_NEAR(info[5], 1000.0, 1e-9);
      EXPECT_NEAR(info[1], 0.0, 1e-12);
    }
    if (tag == "EDGE_SE2_XY") {
      ++edges_xy;
      int i, j;
      double x, y, info[3];
      fields >> i >> j >> x >> y >> info[0] >> info[1] >> info[2];
      EXPECT_EQ(j, 3);  // the landmark's vertex follows the three poses
      EXPECT_NEAR(info[0], 25.0, 1e-9);
    }
  }
  EXPECT_EQ(vertices_se2, 3);
  EXPECT_EQ(vertices_xy, 1);
  EXPECT_EQ(fixed, 1);
  EXPECT_EQ(edges_se2, 2);
  EXPECT_EQ(edges_xy, 3);
}

TEST(G2oWriter, RangeBearingBecomesAPointWithPropagatedInformation) {
  FactorGraph g;
  g.poses = {{0.0, -1, 0, Pose2{}}};
  g.landmarks = {{4, Vec2(0.0, 2.0)}};
  g.range_bearings.push_back({0, 0, Vec2(2.0, kPi / 2), Vec2(0.01, 0.0001).asDiagonal()});
  const std::string path = temp_path("rb.g2o");
  write_g2o(g, path);
  std::ifstream in(path);
  std::string line;
  bool found = false;
  while (std::getline(in, line)) {
    if (line.rfind("EDGE_SE2_XY", 0) != 0) continue;
    found = true;
    std::istringstream fields(line.substr(12));
    int i, j;
    double x, y, ixx, ixy, iyy;
    fields >> i >> j >> x >> y >> ixx >> ixy >> iyy;
    EXPECT_NEAR(x, 0.0, 1e-12);
    EXPECT_NEAR(y, 2.0, 1e-12);
    // Straight left: range error along y (sigma 0.1 m), bearing error along -x (2 m * 0.01 rad = 0.02 m).
    EXPECT_NEAR(iyy, 100.0, 1e-6);
    EXPECT_NEAR(ixx, 1.0 / (0.02 * 0.02), 1e-6);
    EXPECT_NEAR(ixy, 0.0, 1e-6);
  }
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace arbor
