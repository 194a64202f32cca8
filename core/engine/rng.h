// Counter-based random numbers: Philox4x32-10 (Salmon, Moraes, Dror & Shaw, "Parallel random numbers: as easy
// as 1, 2, 3", SC 2011). A stream is keyed by (seed, step, particle, purpose), so every particle draws the same
// numbers whatever thread runs it and whatever the thread count: the property that makes runs bit-identical.
// The normal deviates use our own Box-Muller transform, because the standard library does not specify its
// distributions bit-exactly (engines yes, distributions no).
#ifndef ARBOR_CORE_ENGINE_RNG_H_
#define ARBOR_CORE_ENGINE_RNG_H_

#include <array>
#include <cmath>
#include <cstdint>

#include <Eigen/Eigenvalues>

#include "core/math/angles.h"
#include "core/math/eigen_types.h"

namespace arbor {

// What a stream is used for; part of the key so that two uses never share numbers.
enum class RandomPurpose : std::uint32_t {
  kMotion = 1,
  kProposal = 2,
  kResample = 3,
  kSimulation = 4,
  kWorld = 5,
  kProblem = 6,
  kSurvey = 7,
  kMove = 8,
};

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t step, std::uint64_t particle, RandomPurpose purpose)
      : key_{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32)},
        counter_{static_cast<std::uint32_t>(step), static_cast<std::uint32_t>(step >> 32),
                 static_cast<std::uint32_t>(particle), static_cast<std::uint32_t>(purpose) << 24} {
    counter_[3] ^= static_cast<std::uint32_t>(particle >> 32) & 0x00FFFFFFu;
  }

  std::uint32_t next_u32() {
    if (used_ == 4) refill();
    return block_[used_++];
  }
  // Uniform in (0, 1): 53 random bits, never exactly 0 (safe for log) nor 1.
  double uniform() {
    const std::uint64_t hi = next_u32() >> 5, lo = next_u32() >> 6;  // 27 + 26 bits
    return (static_cast<double>((hi << 26) | lo) + 0.5) * (1.0 / 9007199254740992.0);
  }
  // Standard normal by Box-Muller; values come in pairs, the second is kept for the next call.
  double normal() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const double radius = std::sqrt(-2.0 * std::log(uniform()));
    const double angle = 2.0 * kPi * uniform();
    spare_ = radius * std::sin(angle);
    has_spare_ = true;
    return radius * std::cos(angle);
  }

 private:
  static constexpr std::uint32_t kMul0 = 0xD2511F53u, kMul1 = 0xCD9E8D57u;
  static constexpr std::uint32_t kWeyl0 = 0x9E3779B9u, kWeyl1 = 0xBB67AE85u;

  void refill() {
    std::array<std::uint32_t, 4> c = counter_;
    // The block index is added into c[3]'s low 24 bits (the purpose sits in the high 8).
    c[3] = (c[3] & 0xFF000000u) | ((c[3] + block_index_) & 0x00FFFFFFu);
    std::array<std::uint32_t, 2> k = key_;
    for (int round = 0; round < 10; ++round) {
      const std::uint64_t p0 = static_cast<std::uint64_t>(kMul0) * c[0];
      const std::uint64_t p1 = static_cast<std::uint64_t>(kMul1) * c[2];
      c = {static_cast<std::uint32_t>(p1 >> 32) ^ c[1] ^ k[0], static_cast<std::uint32_t>(p1),
           static_cast<std::uint32_t>(p0 >> 32) ^ c[3] ^ k[1], static_cast<std::uint32_t>(p0)};
      k[0] += kWeyl0;
      k[1] += kWeyl1;
    }
    block_ = c;
    ++block_index_;
    used_ = 0;
  }

  std::array<std::uint32_t, 2> key_;
  std::array<std::uint32_t, 4> counter_;
  std::array<std::uint32_t, 4> block_{};
  std::uint32_t block_index_ = 0;
  int used_ = 4;
  bool has_spare_ = false;
  double spare_ = 0.0;
};

// The draws behind one vector, in a fixed order. The arguments of one call are evaluated in an unspecified
// order (gcc: the last first; clang: the first first), so Vec3(rng.normal(), rng.normal(), rng.normal())
// gave different numbers under the two compilers, and a seed named a different world or run. These draw the
// last component first, the order in which every figure Arbor has published so far was made (gcc's), so
// those stay reproducible under either compiler.
template <class Draw>
Vec2 draw_vec2(Draw&& draw) {
  const double y = draw();
  const double x = draw();
  return {x, y};
}
template <class Draw>
Vec3 draw_vec3(Draw&& draw) {
  const double z = draw();
  const double y = draw();
  const double x = draw();
  return {x, y, z};
}

// Draws from N(mean, cov) with a symmetric square root, robust to a semi-definite covariance.
inline Vec3 sample_gaussian(const Vec3& mean, const Mat3& cov, RandomStream& rng) {
  Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (cov + cov.transpose()));
  const Vec3 n = draw_vec3([&] { return rng.normal(); });
  const Vec3 scaled = eig.eigenvalues().cwiseMax(0.0).cwiseSqrt().cwiseProduct(n);
  return mean + eig.eigenvectors() * scaled;
}

}  // namespace arbor

#endif  // ARBOR_CORE_ENGINE_RNG_H_
