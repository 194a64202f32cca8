// The exchange format: round trip, prediction order, and errors that name file, line and field.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "tests/association/test_problems.h"
#include "core/io/input_error.h"
#include "variants/association/jcbb.h"
#include "variants/association/problem_generator.h"
#include "variants/association/problem_io.h"

namespace arbor {
namespace {

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("arbor_assoc_io_" + name)).string();
}

std::string write_text(const std::string& name, const std::string& text) {
  const std::string path = temp_path(name);
  std::ofstream(path) << text;
  return path;
}

TEST(ProblemIo, RoundTripGivesTheSameProblemAndAnswer) {
  const ProblemGeneratorOptions g{.landmarks = 30, .observations = 8, .clutter = 3, .seed = 11};
  const GeneratedProblem gen = generate_association_problem(g);
  const std::string path = temp_path("roundtrip.txt");
  write_association_problem(path, gen.problem);
  write_association_truth(path + ".truth", gen.truth);
  const AssociationProblem back = read_association_problem(path);
  ASSERT_EQ(back.measurements.size(), gen.problem.measurements.size());
  ASSERT_EQ(back.candidates.size(), gen.problem.candidates.size());
  for (std::size_t i = 0; i < back.measurements.size(); ++i) EXPECT_EQ(back.measurements[i].z, gen.problem.measurements[i].z);
  for (int a = 0; a < 30; ++a)
    for (int b = 0; b < 30; ++b)
      EXPECT_TRUE(back.innovation_covariance(a, b).isApprox(gen.problem.innovation_covariance(a, b), 1e-14));
  EXPECT_EQ(testing::solve_with<Jcbb>(back).pairing, testing::solve_with<Jcbb>(gen.problem).pairing);
  EXPECT_EQ(read_association_truth(path + ".truth", 11), gen.truth);
}

TEST(ProblemIo, PredictionsAreSortedByIdWithTheirCovariance) {
  const std::string path = write_text("order.txt",
                                      "arbor-association-problem 1\n"
                                      "observations 1\n5 0.1\n"
                                      "predictions 2\n9 5 0.1\n2 7 -1\n"
                                      "covariance\n"
                                      "1 0 0.5 0\n0 2 0 0\n0.5 0 3 0\n0 0 0 4\n");
  const AssociationProblem p = read_association_problem(path);
  ASSERT_EQ(p.candidates.size(), 2u);
  EXPECT_EQ(p.candidates[0].id, 2);
  EXPECT_EQ(p.candidates[1].id, 9);
  EXPECT_DOUBLE_EQ(p.innovation_covariance(0, 0)(0, 0), 3.0);
  EXPECT_DOUBLE_EQ(p.innovation_covariance(1, 1)(1, 1), 2.0);
  EXPECT_DOUBLE_EQ(p.innovation_covariance(0, 1)(0, 0), 0.5);
  EXPECT_EQ(testing::solve_with<Jcbb>(p).pairing, (std::vector<LandmarkId>{9}));
}

struct Malformed {
  const char* name;
  const char* text;
  int line;
  const char* field;
};

class ProblemIoErrors : public ::testing::TestWithParam<Malformed> {};

TEST_P(ProblemIoErrors, NameFileLineAndField) {
  const Malformed& c = GetParam();
  const std::string path = write_text(std::string(c.name) + ".txt", c.text);
  try {
    read_association_problem(path);
    FAIL() << "no error for " << c.name;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.line(), c.line) << e.what();
    EXPECT_EQ(e.field(), c.field) << e.what();
  }
}

#define HEADER "arbor-association-problem 1\n"
INSTANTIATE_TEST_SUITE_P(
    Cases, ProblemIoErrors,
    ::testing::Values(
        Malformed{"magic", "arbor-problem 1\n", 1, "header"},
        Malformed{"version", "arbor-association-problem 2\n", 1, "version"},
        Malformed{"count", HEADER "observations two\n", 2, "observations count"},
        Malformed{"keyword", HEADER "predictions 1\n", 2, "observations"},
        Malformed{"bad_number", HEADER "observations 1\n5 x\n", 3, "phi"},
        Malformed{"negative_range", HEADER "observations 1\n-5 0\n", 3, "r"},
        Malformed{"truncated", HEADER "# comment\nobservations 2\n5 0\n", 5, "observation"},
        // A count the file's bytes cannot hold fails before anything is allocated for it.
        Malformed{"count_beyond_the_file", HEADER "observations 0\npredictions 10000000\n", 3, "predictions count"},
        Malformed{"observations_beyond_the_file", HEADER "observations 9000\n", 2, "observations count"},
        Malformed{"observations_beyond_the_budget", HEADER "observations 20000\n", 2, "observations count"},
        Malformed{"short_line", HEADER "observations 1\n5\n", 3, "#2"},
        Malformed{"duplicate_id", HEADER "observations 0\npredictions 2\n1 5 0\n1 6 0\ncovariance\n"
                                  "1 0 0 0\n0 1 0 0\n0 0 1 0\n0 0 0 1\n", 5, "id"},
        Malformed{"asymmetric", HEADER "observations 0\npredictions 1\n1 5 0\ncovariance\n1 0.5\n0.2 1\n", 7,
                  "covariance[1][0]"},
        Malformed{"not_pd", HEADER "observations 0\npredictions 1\n1 5 0\ncovariance\n1 2\n2 1\n", 5, "covariance"},
        Malformed{"short_row", HEADER "observations 0\npredictions 1\n1 5 0\ncovariance\n1 0\n0\n", 7, "#2"},
        Malformed{"trailing", HEADER "observations 0\npredictions 0\ncovariance\nextra\n", 5, ""}),
    [](const ::testing::TestParamInfo<Malformed>& info) { return std::string(info.param.name); });

TEST(ProblemIo, MissingFileIsAnInputError) {
  EXPECT_THROW(read_association_problem(temp_path("does_not_exist.txt")), InputError);
}

TEST(ProblemIo, TruthMustMatchTheObservations) {
  const std::string path = write_text("truth.txt", "3\n-1\n");
  EXPECT_THROW(read_association_truth(path, 3), InputError);
  const std::string bad = write_text("truth_bad.txt", "3\n-7\n");
  EXPECT_THROW(read_association_truth(bad, 2), InputError);
}

}  // namespace
}  // namespace arbor
