// One rule for every numeric option of every subcommand, applied in one place (main.cc) instead of per
// option: a number must be finite (CLI11 reads "nan" and "inf" into a double, and its Range validators let
// NaN through, since every comparison with NaN is false), and an unsigned one has no minus sign (CLI11
// reads "-1" into an unsigned 64-bit seed as 2^64 - 1). Ranges stay with each option.
#ifndef ARBOR_EXPERIMENTS_CLI_NUMERIC_OPTIONS_H_
#define ARBOR_EXPERIMENTS_CLI_NUMERIC_OPTIONS_H_

#include <CLI/CLI.hpp>

namespace arbor::cli {

// For an unsigned option (seeds, counts): refuses a value with a leading minus sign.
const CLI::Validator& unsigned_number();

// For a probability that feeds a chi-square quantile: strictly inside (0, 1).
const CLI::Validator& open_probability();

// Walks every option of app and its subcommands: an option whose default value is a finite number gets the
// "finite number" check. Call after every subcommand is added and before parsing.
void require_finite_numbers(CLI::App& app);

}  // namespace arbor::cli

#endif  // ARBOR_EXPERIMENTS_CLI_NUMERIC_OPTIONS_H_
