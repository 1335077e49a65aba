// The table of agent::NormalCdf: per interval the Chebyshev interpolant of Phi at kDegree + 1
// points, in powers of the interval's coordinate v in [-1/2, 1/2], computed in long double so
// that the doubles kept are Phi's to their last bits.
#include <agent/normal_cdf.h>

#include <cmath>

namespace agent {

namespace {

using Real = long double;

Real phi_of(Real z) { return 0.5L * std::erfc(-z / std::sqrt(Real(2))); }

constexpr int kPoints = NormalCdf::kDegree + 1;

/// The Chebyshev points on [-1, 1] and cos(pi j (2 k + 1) / (2 n)) (T_j at point k): the same for
/// every interval, so taken once.
struct ChebyshevPoints {
  Real point[kPoints], t[kPoints][kPoints];
  ChebyshevPoints() {
    const Real pi = std::acos(Real(-1));
    for (int k = 0; k < kPoints; ++k) point[k] = std::cos(pi * (2 * k + 1) / (2 * kPoints));
    for (int j = 0; j < kPoints; ++j)
      for (int k = 0; k < kPoints; ++k) t[j][k] = std::cos(pi * j * (2 * k + 1) / (2 * kPoints));
  }
};

/// Monomial coefficients of the interpolant of Phi on [a, b] at the Chebyshev points, in powers of
/// v = u / 2 (u in [-1, 1] across the interval).
void fit_interval(const ChebyshevPoints& cheb, Real a, Real b, double* out) {
  constexpr int n = kPoints;
  Real values[n];
  for (int k = 0; k < n; ++k) values[k] = phi_of(0.5L * (a + b) + 0.5L * (b - a) * cheb.point[k]);
  // Chebyshev coefficients c_j, then sum c_j T_j(u) in powers of u (T_j by its recurrence).
  Real mono[n] = {}, t_prev[n] = {}, t_this[n] = {}, t_next[n] = {};
  t_prev[0] = 1;  // T_0
  t_this[1] = 1;  // T_1
  for (int j = 0; j < n; ++j) {
    Real c = 0;
    for (int k = 0; k < n; ++k) c += values[k] * cheb.t[j][k];
    c *= (j == 0 ? 1.0L : 2.0L) / n;
    const Real* t = j == 0 ? t_prev : t_this;
    for (int i = 0; i < n; ++i) mono[i] += c * t[i];
    if (j == 0) continue;
    for (int i = 0; i < n; ++i) t_next[i] = (i > 0 ? 2 * t_this[i - 1] : 0) - t_prev[i];
    for (int i = 0; i < n; ++i) {
      t_prev[i] = t_this[i];
      t_this[i] = t_next[i];
    }
  }
  Real scale = 1;  // u^i = 2^i v^i
  for (int i = 0; i < n; ++i, scale *= 2) out[i] = double(mono[i] * scale);
}

}  // namespace

NormalCdf::NormalCdf() {
  const ChebyshevPoints cheb;
  for (int i = 0; i < kIntervals; ++i)  // interval i centred at -kReach + i / kPerUnit
    fit_interval(cheb, -kReach + (i - 0.5L) / kPerUnit, -kReach + (i + 0.5L) / kPerUnit, coefficients_[i]);
}

const NormalCdf& NormalCdf::table() {
  static const NormalCdf cdf;
  return cdf;
}

const ExactNormalCdf& ExactNormalCdf::table() {
  static const ExactNormalCdf cdf;
  return cdf;
}

}  // namespace agent
