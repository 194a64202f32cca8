// The physical limits of Arbor's input (docs/scenario_format.md, "Limits") and the field readers that apply
// them. Every reader goes through these: scenarios, the dataset converters and the iSAM file, so a value the
// engine cannot square or invert safely is an input error naming file, line and field at the first reader
// that sees it, never an abort or a NaN inside the engine, and never an error about a file the user did not
// write.
#ifndef ARBOR_CORE_IO_FIELD_LIMITS_H_
#define ARBOR_CORE_IO_FIELD_LIMITS_H_

#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/io/text_reader.h"

namespace arbor {

// Far outside any real robot's figures, and inside what double arithmetic squares and inverts safely (a
// denormal sigma makes a singular covariance; a control of 1e300 m overflows when squared).
namespace scenario_limits {
inline constexpr double kMaxCoordinate = 1e9;      // |x|, |y| of poses, landmarks and GPS fixes [m]
// |x|, |y| of an estimated pose (a run's trajectory.tum): a diverged filter can drift past kMaxCoordinate on
// controls at their limit, and its output must stay readable; squares stay far inside double range.
inline constexpr double kMaxEstimateCoordinate = 1e15;
inline constexpr double kMaxTime = 1e12;           // |t| [s]
inline constexpr double kMaxRange = 1e6;           // measured ranges and sensor ranges [m]
inline constexpr double kMinSigmaRange = 1e-6;     // [m]
inline constexpr double kMinSigmaBearing = 1e-9;   // [rad]
inline constexpr double kMaxSigma = 1e3;           // any standard deviation [m, rad or signature units]
inline constexpr double kMaxNoiseDensity = 1e6;    // motion noise densities
inline constexpr double kMaxControl = 1e6;         // |u| of each control field (speeds, angles, odometry)
inline constexpr double kMaxSignature = 1e6;       // |signature|
// An Ackermann step's steering angle: below the converters' lock limit, and short of where the axle-centre
// speed v_e / (1 - tan(steering) * encoder_offset / wheelbase) blows up: that denominator must stay at least
// kMinSteeringDenominator (the axle at most 10 times the encoder's speed; the ACFR ute at its lock gives 0.31).
inline constexpr double kMaxSteering = 1.2;             // |steering| [rad]
inline constexpr double kMinSteeringDenominator = 0.1;
inline constexpr int kMaxMeasurementsPerScan = 10'000;  // a budget: every strategy's work grows with it
// A map.csv landmark's variances (cov_xx, cov_yy) and |cov_xy|: far beyond what any filter writes, and inside
// the range where their products (the determinant, the engine's H P H^T) neither overflow nor underflow to 0.
inline constexpr double kMinMapVariance = 1e-100;
inline constexpr double kMaxMapVariance = 1e100;
// Landmark ids (truth ids, a prior map's ids) end at 2^30 - 1: the filter numbers the landmarks it starts after
// a prior map's largest id, and a 32-bit id must not overflow there.
inline constexpr std::int32_t kMaxLandmarkId = (1 << 30) - 1;
}  // namespace scenario_limits

// Field i of the current line as a number within [lo, hi]; the error names the field and the limits.
double number_within(const TextReader& in, std::size_t i, std::string_view name, double lo, double hi);
// Within [0, hi], with a message that says "negative" when it is.
double non_negative_within(const TextReader& in, std::size_t i, std::string_view name, double hi);

// The quantities every format shares, each within its limit.
double coordinate_field(const TextReader& in, std::size_t i, std::string_view name);  // [m]
double time_field(const TextReader& in, std::size_t i, std::string_view name);        // [s]
double control_field(const TextReader& in, std::size_t i, std::string_view name);     // speeds, angles
// Integer milliseconds (Victoria Park's clock) within kMaxTime.
std::int64_t time_ms_field(const TextReader& in, std::size_t i, std::string_view name);
double range_field(const TextReader& in, std::size_t i, std::string_view name);       // [0, kMaxRange] m
// A landmark id: within [0, kMaxLandmarkId].
std::int32_t landmark_id_field(const TextReader& in, std::size_t i, std::string_view name);

}  // namespace arbor

#endif  // ARBOR_CORE_IO_FIELD_LIMITS_H_
