#pragma once
// The seed's literal angle correction, the reference the library's robust projection is tested
// against (test code: the library does not use it).
#include <pbd/particles.h>

#include <algorithm>
#include <cmath>

namespace pbd_test {

using pbd::Vec3;

/// The seed's PBD correction (CN104268305A step 4d, reconstructed as in Mueller et al. 2007,
/// appendix A) in its q notation with stiffness k: dp_j = -k w_j sqrt(1-d^2) (acos d - theta0) q_j
/// / sum_m w_m |q_m|^2. Literal (acos form, NaN at d = -1): kept only as the reference the
/// robust form is tested against. Returns false where sqrt(1-d^2) or the denominator vanish.
inline bool seed_angle_correction(const Vec3& p1, const Vec3& p2, const Vec3& p3, double w1, double w2, double w3,
                                  double theta0, double k, Vec3& dp1, Vec3& dp2, Vec3& dp3) {
  const double L1 = (p1 - p3).norm(), L2 = (p2 - p3).norm();
  const Vec3 n1 = (p2 - p3) / L2, n2 = (p1 - p3) / L1;
  const double d = n1.dot(n2);
  const Vec3 q1 = (d * n2 - n1) / L1;
  const Vec3 q2 = (d * n1 - n2) / L2;
  const Vec3 q3 = -q1 - q2;
  const double den = w1 * q1.squaredNorm() + w2 * q2.squaredNorm() + w3 * q3.squaredNorm();
  const double root = std::sqrt(std::max(0.0, 1 - d * d));
  if (!(root > 0) || !(den > 0)) return false;
  const double f = -k * root * (std::acos(d) - theta0) / den;
  dp1 = f * w1 * q1;
  dp2 = f * w2 * q2;
  dp3 = f * w3 * q3;
  return true;
}

}  // namespace pbd_test
