// Rules for every option of every subcommand, applied in one place (main.cc) instead of per option:
//   * no option takes an empty value (`run --out ""` printed "wrote /result.json" and wrote nothing);
//   * a number must be finite (CLI11 reads "nan" and "inf" into a double, and its Range validators let NaN
//     through, since every comparison with NaN is false);
//   * an unsigned one has no minus sign (CLI11 reads "-1" into an unsigned 64-bit seed as 2^64 - 1) and fits
//     in 64 bits (CLI11 clamps a larger one to 2^64 - 1).
// Ranges stay with each option.
#ifndef ARBOR_EXPERIMENTS_OPTIONS_OPTION_CHECKS_H_
#define ARBOR_EXPERIMENTS_OPTIONS_OPTION_CHECKS_H_

#include <CLI/CLI.hpp>

namespace arbor::cli {

// The most worker threads an option may ask for (run, smooth, a sweep's grid): far above any machine Arbor
// runs on, and far below the counts that made TBB's arena crash (10^7 segfaulted) or Ceres allocate per
// thread without bound (10^9 hung, growing memory) before they could say anything.
inline constexpr int kMaxThreads = 1024;

// For an unsigned option (seeds, counts): refuses a value with a leading minus sign or beyond 2^64 - 1.
const CLI::Validator& unsigned_number();

// For a probability that feeds a chi-square quantile: strictly inside (0, 1).
const CLI::Validator& open_probability();

// Range checks whose messages print the bounds as written ("must be at least 0 (got -1)"); CLI11's own
// NonNegativeNumber and PositiveNumber print the largest double in full, 309 digits.
CLI::Validator at_least(double minimum);
CLI::Validator within(double minimum, double maximum);

// Walks every option of app and its subcommands: each gets the non-empty check, and one whose default value
// is a finite number the finite-number check. Call after every subcommand is added and before parsing.
void apply_common_option_checks(CLI::App& app);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_OPTIONS_OPTION_CHECKS_H_
