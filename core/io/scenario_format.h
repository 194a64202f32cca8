// Reading and writing the scenario text format (docs/scenario_format.md): one path into the engine for
// simulated and real data alike.
#ifndef ARBOR_CORE_IO_SCENARIO_FORMAT_H_
#define ARBOR_CORE_IO_SCENARIO_FORMAT_H_

#include <string>

#include "core/io/scenario.h"

namespace arbor {

// The physical limits of a scenario (docs/scenario_format.md, "Limits"): a value outside them is an input
// error at the reader, never an abort or a NaN inside the engine. They are far outside any real robot's
// figures, and inside what double arithmetic squares and inverts safely (a denormal sigma makes a singular
// covariance; a control of 1e300 m overflows when squared).
namespace scenario_limits {
inline constexpr double kMaxCoordinate = 1e9;      // |x|, |y| of poses, landmarks and GPS fixes [m]
inline constexpr double kMaxTime = 1e12;           // |t| [s]
inline constexpr double kMaxRange = 1e6;           // measured ranges and sensor ranges [m]
inline constexpr double kMinSigmaRange = 1e-6;     // [m]
inline constexpr double kMinSigmaBearing = 1e-9;   // [rad]
inline constexpr double kMaxSigma = 1e3;           // any standard deviation [m, rad or signature units]
inline constexpr double kMaxNoiseDensity = 1e6;    // motion noise densities
inline constexpr double kMaxControl = 1e6;         // |u| of each control field
inline constexpr double kMaxSignature = 1e6;       // |signature|
inline constexpr int kMaxMeasurementsPerScan = 10'000;  // a budget: every strategy's work grows with it
}  // namespace scenario_limits

// Throws InputError naming file, line and field on anything malformed: truncation, non-numeric or
// non-finite values, values outside scenario_limits, negative ranges, times going backwards, unknown line
// types, missing or repeated one-off lines.
Scenario read_scenario(const std::string& path);

// Writes with shortest round-trip number formatting, so read_scenario(write_scenario(s)) == s exactly.
// The file is written to a temporary name and renamed, so a crash never leaves a partial scenario. The text
// is read back with read_scenario before the rename: a writer never emits a file its reader rejects, and
// throws that InputError (naming path, the line of the text and the field) instead.
void write_scenario(const Scenario& scenario, const std::string& path);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_SCENARIO_FORMAT_H_
