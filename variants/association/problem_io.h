// The association-problem exchange format of DESIGN.md §4, so any library can be compared with Arbor on
// identical problems, plus the ground-truth sidecar written by the generator.
//   arbor-association-problem 1
//   observations M        then M lines: r phi            (range m, bearing rad)
//   predictions N         then N lines: id r phi         (predicted measurement of landmark id)
//   covariance            then 2N lines of 2N numbers: joint covariance of the predictions, R included
// '#' starts a comment line. Truth sidecar: one line per observation, the true landmark id or -1 (clutter).
#ifndef ARBOR_VARIANTS_ASSOCIATION_PROBLEM_IO_H_
#define ARBOR_VARIANTS_ASSOCIATION_PROBLEM_IO_H_

#include <string>
#include <vector>

#include "core/association/association_problem.h"

namespace arbor {

// Reads a problem; throws InputError naming file, line and field for anything malformed (bad header, counts
// that do not match, a non-finite or negative range, duplicate ids, a covariance that is not symmetric or
// not positive definite). Predictions are stored sorted by id (the covariance permuted with them); the joint
// covariance goes to problem.joint_covariance. Pose-free strategies need world positions, which the format
// does not carry: each candidate's position is its predicted point in the prior robot frame and
// position_cov = J C_jj J^T (R already included, so problem.R is zero).
AssociationProblem read_association_problem(const std::string& path);

// Writes problem in the exchange format (17 significant digits: reading it back gives the same numbers).
// The covariance is innovation_covariance(a, b) over all candidates: 2N x 2N, so keep N in the thousands.
void write_association_problem(const std::string& path, const AssociationProblem& problem);

// Ground-truth sidecar: one id per observation, -1 for clutter.
std::vector<LandmarkId> read_association_truth(const std::string& path, int observations);
void write_association_truth(const std::string& path, const std::vector<LandmarkId>& truth);

}  // namespace arbor

#endif  // ARBOR_VARIANTS_ASSOCIATION_PROBLEM_IO_H_
