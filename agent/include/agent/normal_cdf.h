#pragma once
// The standard normal distribution function Phi(z) = 0.5 erfc(-z / sqrt 2) without a
// transcendental call: the turning paths' deposit takes it once per direction, agent edge and
// image (docs/agent-model.md, "Deposit"), and std::erfc there was two fifths of a 2D solve.
#include <cmath>
#include <cstdint>
#include <cstring>

namespace agent {

/// Phi(z) from a table of polynomials: on [-10, 0], one of degree 7 per sixteenth of a unit of z
/// (its Chebyshev interpolant, fitted once per process in long double); for z > 0, 1 - Phi(-z);
/// below -10, Phi(-10) (8e-24). Accuracy (tests/agent/test_normal_cdf.cc, against
/// 0.5 erfc(-z / sqrt 2)): within 2e-16 absolute everywhere, and 1e-11 relative for z >= -8.
class NormalCdf {
 public:
  static constexpr int kDegree = 7;    ///< 8 coefficients: an interval is one 64 B line
  static constexpr int kPerUnit = 16;  ///< intervals per unit of z
  static constexpr double kReach = 10; ///< the table's intervals are centred on [-kReach, 0]
  static constexpr int kIntervals = int(kReach) * kPerUnit + 1;

  /// The table, fitted on the first call (thread-safe).
  static const NormalCdf& table();

  double operator()(double z) const {
    double t = -std::abs(z);        // the lower half; the upper by symmetry, rounded at 1
    t = t > -kReach ? t : -kReach;  // below -10 (or NaN): -10
    const double p = lower(t);
    return z > 0 ? 1 - p : p;
  }

  /// Phi(t) for t in [-kReach, 0] (not checked): what operator() takes, for loops that know the
  /// sign of their z and their range (no test, no choice per call).
  double lower(double t) const {
    const double ts = t * kPerUnit;  // exact (a power of 2), in [-160, 0]
    // ts rounded to the nearest whole number m: 160 + m is interval i, in the low bits of
    // ts + 160 + 1.5 2^52 (no conversion to int and back; needs IEEE doubles rounding to
    // nearest, as C++ has them without -ffast-math). v = ts - m exactly: t's every bit counts.
    constexpr double kRound = 6755399441055744.0 + kReach * kPerUnit;
    const double r = ts + kRound;
    std::uint64_t bits;
    std::memcpy(&bits, &r, sizeof bits);
    const double v = ts - (r - kRound);  // in [-1/2, 1/2] across interval i
    const double* c = coefficients_[bits & 0xffff];
    // Estrin's scheme: short chains, so that the edges' evaluations overlap
    const double v2 = v * v, v4 = v2 * v2;
    return ((c[0] + c[1] * v) + v2 * (c[2] + c[3] * v)) + v4 * ((c[4] + c[5] * v) + v2 * (c[6] + c[7] * v));
  }

 private:
  NormalCdf();
  alignas(64) double coefficients_[kIntervals][kDegree + 1];  ///< per interval, in powers of v
};

/// Phi(z) (NormalCdf::table()); loops take the table once and call it.
inline double normal_cdf(double z) { return NormalCdf::table()(z); }

/// Phi(z) = 0.5 std::erfc(-z / sqrt 2): what NormalCdf stands for, called where ExactFunctions
/// (agent/exact_functions.h) asks for it. The same interface as NormalCdf.
struct ExactNormalCdf {
  static const ExactNormalCdf& table();
  double operator()(double z) const { return 0.5 * std::erfc(-z / std::sqrt(2.0)); }
  double lower(double t) const { return (*this)(t); }
};

}  // namespace agent
