// Reader and writer of the association-problem exchange format (DESIGN.md §4).
#include "variants/association/problem_io.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <numeric>
#include <string_view>
#include <system_error>

#include <Eigen/Cholesky>
#include <fmt/core.h>
#include <fmt/format.h>

#include "core/io/atomic_file.h"
#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/io/text_reader.h"
#include "core/math/angles.h"
#include "core/models/range_bearing_model.h"

namespace arbor {
namespace {

constexpr std::string_view kMagic = "arbor-association-problem";
constexpr int kVersion = 1;
// Relative tolerance of the symmetry check: files written with fewer digits still read.
constexpr double kSymmetryTolerance = 1e-6;

// Reads the next data line or fails with "expected <what>".
void require_line(TextReader& in, std::string_view what) {
  if (!in.next()) throw InputError(in.path(), in.line_number() + 1, std::string(what), "unexpected end of file");
}

// "<keyword> <count>" with a non-negative count. A count promises lines: it is checked against the bytes
// the file holds, at least bytes_per_item(count) for the items it announces, before anything is allocated for
// them (a 64-byte file that declared 10^7 predictions reached 1.9 GB before it failed).
template <class BytesPerItem>
int read_count(TextReader& in, std::string_view keyword, std::int64_t max_count, std::uintmax_t file_bytes,
               BytesPerItem bytes_for) {
  require_line(in, keyword);
  if (in.field(0) != keyword)
    in.fail(std::string(keyword), fmt::format("expected '{} COUNT', found '{}'", keyword, in.field(0)));
  in.expect_fields(2, 2, keyword);
  const std::string field = fmt::format("{} count", keyword);
  const std::int64_t count = in.integer(1, field);
  if (count < 0 || count > max_count) in.fail(field, fmt::format("{} is outside [0, {}]", count, max_count));
  const double needed = bytes_for(static_cast<double>(count));
  if (needed > static_cast<double>(file_bytes))
    in.fail(field, fmt::format("{} {} need at least {:.0f} bytes; the file has {}", count, keyword, needed, file_bytes));
  return static_cast<int>(count);
}

Vec2 read_range_bearing(TextReader& in, std::size_t first) {
  const double r = in.number(first, "r");
  const double phi = in.number(first + 1, "phi");
  if (r < 0.0) in.fail("r", fmt::format("range {} is negative", r));
  return {r, wrap_angle(phi)};
}

}  // namespace

AssociationProblem read_association_problem(const std::string& path) {
  TextReader in(path);
  AssociationProblem problem;
  problem.R = Mat2::Zero();
  require_line(in, "header");
  in.expect_fields(2, 2, "header");
  if (in.field(0) != kMagic) in.fail("header", fmt::format("expected '{} {}'", kMagic, kVersion));
  if (in.integer(1, "version") != kVersion) in.fail("version", fmt::format("only version {} is known", kVersion));

  std::error_code size_error;
  const std::uintmax_t file_bytes = std::filesystem::file_size(path, size_error);
  // An observation line is at least "r phi\n" (4 bytes); a prediction line "id r phi\n" (6 bytes) and its two
  // covariance rows of 2n numbers (2 bytes each with the separator).
  // Observations: the scan budget of the scenario format (every strategy's work grows with it). Predictions:
  // bounded by the bytes their dense covariance needs.
  const int m = read_count(in, "observations", scenario_limits::kMaxMeasurementsPerScan, file_bytes,
                           [](double k) { return 4.0 * k; });
  problem.measurements.resize(m);
  for (int i = 0; i < m; ++i) {
    require_line(in, "observation");
    in.expect_fields(2, 2, "observation");
    problem.measurements[i].z = read_range_bearing(in, 0);
  }

  const int n = read_count(in, "predictions", 10'000'000, file_bytes, [](double k) { return 6.0 * k + 8.0 * k * k; });
  std::vector<AssociationCandidate> file_order(n);
  std::vector<int> lines(n);
  for (int j = 0; j < n; ++j) {
    require_line(in, "prediction");
    in.expect_fields(3, 3, "prediction");
    const std::int64_t id = in.integer(0, "id");
    if (id < 0 || id > std::numeric_limits<LandmarkId>::max())
      in.fail("id", fmt::format("landmark id {} must be in [0, 2^31)", id));
    file_order[j].id = static_cast<LandmarkId>(id);
    file_order[j].z_hat = read_range_bearing(in, 1);
    lines[j] = in.line_number();
  }

  require_line(in, "covariance");
  in.expect_fields(1, 1, "covariance");
  if (in.field(0) != "covariance") in.fail("covariance", fmt::format("expected 'covariance', found '{}'", in.field(0)));
  Eigen::MatrixXd C(2 * n, 2 * n);
  std::vector<int> row_line(2 * n);
  for (int r = 0; r < 2 * n; ++r) {
    require_line(in, "covariance row");
    in.expect_fields(2 * n, 2 * n, "covariance row");
    for (int c = 0; c < 2 * n; ++c) C(r, c) = in.number(c, fmt::format("covariance[{}][{}]", r, c));
    row_line[r] = in.line_number();
  }
  if (in.next()) in.fail("", "unexpected data after the covariance matrix");
  for (int r = 0; r < 2 * n; ++r) {
    if (!(C(r, r) > 0.0))
      throw InputError(path, row_line[r], fmt::format("covariance[{}][{}]", r, r), "diagonal entry must be positive");
    for (int c = 0; c < r; ++c) {
      const double scale = std::max({std::abs(C(r, c)), std::abs(C(c, r)), 1e-300});
      if (std::abs(C(r, c) - C(c, r)) > kSymmetryTolerance * scale)
        throw InputError(path, row_line[r], fmt::format("covariance[{}][{}]", r, c),
                         fmt::format("{} differs from covariance[{}][{}] = {}: not symmetric", C(r, c), c, r, C(c, r)));
    }
  }
  C = 0.5 * (C + C.transpose()).eval();
  if (n > 0) {
    Eigen::LLT<Eigen::MatrixXd> llt(C);
    if (llt.info() != Eigen::Success)
      throw InputError(path, row_line[0] - 1, "covariance", "matrix is not positive definite");
  }

  // Sort predictions by id (the AssociationProblem invariant) and permute the covariance with them.
  std::vector<int> perm(n);
  std::iota(perm.begin(), perm.end(), 0);
  std::sort(perm.begin(), perm.end(), [&](int a, int b) { return file_order[a].id < file_order[b].id; });
  for (int k = 1; k < n; ++k)
    if (file_order[perm[k]].id == file_order[perm[k - 1]].id)
      throw InputError(path, std::max(lines[perm[k]], lines[perm[k - 1]]), "id",
                       fmt::format("landmark id {} appears twice", file_order[perm[k]].id));
  problem.joint_covariance.resize(2 * n, 2 * n);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      problem.joint_covariance.block<2, 2>(2 * a, 2 * b) = C.block<2, 2>(2 * perm[a], 2 * perm[b]);
  problem.candidates.resize(n);
  const Pose2 origin;
  for (int a = 0; a < n; ++a) {
    AssociationCandidate& cand = problem.candidates[a];
    cand = file_order[perm[a]];
    cand.S = problem.joint_covariance.block<2, 2>(2 * a, 2 * a);
    cand.H_pose.setZero();
    Mat2 J;
    cand.position = range_bearing_inverse(origin, cand.z_hat, &J);
    cand.position_cov = J * cand.S * J.transpose();
  }
  return problem;
}

void write_association_problem(const std::string& path, const AssociationProblem& problem) {
  const int m = static_cast<int>(problem.measurements.size());
  const int n = static_cast<int>(problem.candidates.size());
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# Arbor association problem (DESIGN.md §4)\n{} {}\n", kMagic, kVersion);
  fmt::format_to(std::back_inserter(out), "observations {}\n", m);
  for (const auto& z : problem.measurements) fmt::format_to(std::back_inserter(out), "{:.17g} {:.17g}\n", z.z.x(), z.z.y());
  fmt::format_to(std::back_inserter(out), "predictions {}\n", n);
  for (const auto& c : problem.candidates)
    fmt::format_to(std::back_inserter(out), "{} {:.17g} {:.17g}\n", c.id, c.z_hat.x(), c.z_hat.y());
  fmt::format_to(std::back_inserter(out), "covariance\n");
  std::vector<Mat2> row(n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) row[b] = problem.innovation_covariance(a, b);
    for (int r = 0; r < 2; ++r) {
      for (int b = 0; b < n; ++b)
        fmt::format_to(std::back_inserter(out), "{}{:.17g} {:.17g}", b == 0 ? "" : " ", row[b](r, 0), row[b](r, 1));
      out.push_back('\n');
    }
  }
  write_file_atomically(path, std::string_view(out.data(), out.size()));
}

std::vector<LandmarkId> read_association_truth(const std::string& path, int observations) {
  TextReader in(path);
  std::vector<LandmarkId> truth;
  while (in.next()) {
    in.expect_fields(1, 1, "truth");
    const std::int64_t id = in.integer(0, "id");
    if (id < -1 || id > std::numeric_limits<LandmarkId>::max()) in.fail("id", "must be a landmark id or -1");
    truth.push_back(static_cast<LandmarkId>(id));
  }
  if (static_cast<int>(truth.size()) != observations)
    throw InputError(path, in.line_number(), "",
                     fmt::format("{} truth lines for {} observations", truth.size(), observations));
  return truth;
}

void write_association_truth(const std::string& path, const std::vector<LandmarkId>& truth) {
  fmt::memory_buffer out;
  fmt::format_to(std::back_inserter(out), "# true landmark id per observation, -1 = clutter\n");
  for (LandmarkId id : truth) fmt::format_to(std::back_inserter(out), "{}\n", id);
  write_file_atomically(path, std::string_view(out.data(), out.size()));
}

}  // namespace arbor
