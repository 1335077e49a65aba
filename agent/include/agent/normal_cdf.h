#pragma once
// The standard normal distribution function Phi(z) = 0.5 erfc(-z / sqrt 2) without a
// transcendental call: the turning paths' deposit takes it once per direction, agent edge and
// image (docs/agent-model.md, "Deposit"), and std::erfc there was two fifths of a 2D solve.
#include <cmath>

namespace agent {

/// Phi(z) from a table of polynomials: on [-10, 0] one of degree 7 per sixteenth of a unit (its
/// Chebyshev interpolant, fitted once per process in long double); for z > 0, 1 - Phi(-z); below
/// -10 (Phi < 8e-24), 0. Accuracy (tests/agent/test_normal_cdf.cc, against
/// 0.5 std::erfc(-z / sqrt 2)): within 1.5e-16 absolute everywhere and 1e-10 relative for
/// z >= -8 (1e-8 down to -10).
class NormalCdf {
 public:
  static constexpr int kDegree = 7;       ///< 8 coefficients: an interval is one 64 B line
  static constexpr int kPerUnit = 16;     ///< intervals per unit of z
  static constexpr double kReach = 10;    ///< the table covers [-kReach, 0]
  static constexpr int kIntervals = int(kReach) * kPerUnit;

  /// The table, fitted on the first call (thread-safe).
  static const NormalCdf& table();

  double operator()(double z) const {
    const double t = -std::abs(z);  // the lower half; the upper by symmetry, rounded at 1
    if (!(t > -kReach)) return z > 0 ? 1.0 : 0.0;
    const double s = (t + kReach) * kPerUnit;
    const int i = s < kIntervals ? int(s) : kIntervals - 1;  // t = 0: the last interval's end
    const double u = 2 * (s - i) - 1;                        // in [-1, 1] across the interval
    const double* c = coefficients_[i];
    // Estrin's scheme: four short chains instead of Horner's seven dependent steps
    const double u2 = u * u, u4 = u2 * u2;
    const double p = ((c[0] + c[1] * u) + u2 * (c[2] + c[3] * u)) + u4 * ((c[4] + c[5] * u) + u2 * (c[6] + c[7] * u));
    return z > 0 ? 1 - p : p;
  }

 private:
  NormalCdf();
  alignas(64) double coefficients_[kIntervals][kDegree + 1];  ///< per interval, in powers of u
};

/// Phi(z) (NormalCdf::table()); loops take the table once and call it.
inline double normal_cdf(double z) { return NormalCdf::table()(z); }

}  // namespace agent
