// Saint-Venant's flexure shear on a rectangle (agent/flexure_shear.h): no traction on the four
// sides, the correction's mean 0 across the width, equilibrium and Beltrami-Michell by finite
// differences, Timoshenko & Goodier's 1.126 on a square, the agent means against quadrature of the
// point values, and no overflow on a deep section.
#include <agent/flexure_shear.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace agent;

namespace {

constexpr double kV = 2.0;  // [N]

double tau0(double y, double h, double d, double V) { return V / (2 * d * h * h * h / 12) * (0.25 * h * h - y * y); }

/// The correction to Jourawski's tau0 at a point: (at - tau0, aw).
FlexureShear correction(double y, double z, double h, double d, double nu) {
  const FlexureShear s = flexure_shear(y, z, h, d, kV, nu);
  return {s.at - tau0(y, h, d, kV), s.aw};
}

}  // namespace

// No traction on the sides: tau_at = 0 at y = +-h/2, tau_aw = 0 at z = +-d/2, on a section as deep
// as wide, twice as deep, and half as deep. On the sides y = +-h/2 the series' terms fall only as
// 1 / n^2 (at the corners its sum converges as 1 / n): the 10^5 terms leave 1e-5 of V / A.
TEST(FlexureShear, TractionFreeSides) {
  for (const auto& [h, d] : {std::pair{0.02, 0.02}, std::pair{0.04, 0.02}, std::pair{0.01, 0.02}}) {
    const double scale = kV / (h * d);  // V / A
    for (double z : {-0.5, -0.31, 0.0, 0.17, 0.44}) {
      EXPECT_NEAR(flexure_shear(0.5 * h, z * d, h, d, kV, 0.3).at, 0.0, 1e-5 * scale) << h << " " << z;
      EXPECT_NEAR(flexure_shear(-0.5 * h, z * d, h, d, kV, 0.3).at, 0.0, 1e-5 * scale) << h << " " << z;
    }
    for (double y : {-0.5, -0.2, 0.0, 0.35}) {
      EXPECT_NEAR(flexure_shear(y * h, 0.5 * d, h, d, kV, 0.3).aw, 0.0, 1e-12 * scale);
      EXPECT_NEAR(flexure_shear(y * h, -0.5 * d, h, d, kV, 0.3).aw, 0.0, 1e-12 * scale);
    }
    // Inside, the shears do not vanish: tau_aw is odd in y and in z.
    const FlexureShear in = flexure_shear(0.3 * h, 0.3 * d, h, d, kV, 0.3);
    EXPECT_GT(std::abs(in.aw), 1e-3 * scale);
    EXPECT_DOUBLE_EQ(flexure_shear(-0.3 * h, 0.3 * d, h, d, kV, 0.3).aw, -in.aw);
    EXPECT_DOUBLE_EQ(flexure_shear(0.3 * h, -0.3 * d, h, d, kV, 0.3).aw, -in.aw);
  }
}

// Timoshenko & Goodier (section 124): a square, nu = 1/4, tau_at at the middle of the sides z =
// +-d/2 is 1.126 of Jourawski's 1.5 V / A (1.5 + 2.4 (1/12 - sum 1 / (n^2 cosh(n pi)) / (2 pi^2))
// = 1.68940); at the centre 1.5 V / A less the same correction's value there.
TEST(FlexureShear, TimoshenkoGoodierSquare) {
  const double d = 0.02, A = d * d;
  const double side = flexure_shear(0, 0.5 * d, d, d, kV, 0.25).at / (1.5 * kV / A);
  EXPECT_NEAR(side, 1.1262636406, 1e-9);
  EXPECT_NEAR(flexure_shear(0, -0.5 * d, d, d, kV, 0.25).at / (1.5 * kV / A), 1.1262636406, 1e-9);
  EXPECT_LT(flexure_shear(0, 0, d, d, kV, 0.25).at, 1.5 * kV / A);
  EXPECT_DOUBLE_EQ(flexure_shear(0, 0.3 * d, d, d, kV, 0.25).aw, 0.0);  // no tau_aw on the neutral axis
  // nu = 0: Jourawski's exactly.
  EXPECT_DOUBLE_EQ(flexure_shear(0.004, 0.006, d, d, kV, 0.0).at, tau0(0.004, d, d, kV));
}

// Equilibrium of the correction, d(at - tau0)/dy + d aw/dz = 0, and Beltrami-Michell, laplacian
// tau_at = -V / ((1 + nu) I) and laplacian tau_aw = 0, by central differences at inner points.
TEST(FlexureShear, EquilibriumAndCompatibility) {
  const double h = 0.02, d = 0.03, nu = 0.3, I = d * h * h * h / 12, e = 1e-5;
  const double k = nu / (1 + nu) * kV / I;
  for (const auto& [y, z] : {std::pair{0.0, 0.0}, std::pair{0.004, -0.009}, std::pair{-0.008, 0.013}, std::pair{0.009, 0.011}}) {
    const double div = (correction(y + e, z, h, d, nu).at - correction(y - e, z, h, d, nu).at) / (2 * e) +
                       (correction(y, z + e, h, d, nu).aw - correction(y, z - e, h, d, nu).aw) / (2 * e);
    EXPECT_NEAR(div, 0.0, 1e-6 * k * d) << y << " " << z;
    auto laplacian = [&](auto part) {
      auto f = [&](double yy, double zz) { return part(flexure_shear(yy, zz, h, d, kV, nu)); };
      return (f(y + e, z) + f(y - e, z) + f(y, z + e) + f(y, z - e) - 4 * f(y, z)) / (e * e);
    };
    EXPECT_NEAR(laplacian([](const FlexureShear& s) { return s.at; }), -kV / ((1 + nu) * I), 1e-3 * kV / I) << y << " " << z;
    EXPECT_NEAR(laplacian([](const FlexureShear& s) { return s.aw; }), 0.0, 1e-3 * kV / I) << y << " " << z;
  }
}

// The agent means: each box's mean is the point values' mean (Gauss-Legendre, 5 x 5 points per box:
// 2e-5 of V / A in the boxes on the sides, where the stress function's corners are not polynomial);
// across the width the at means sum to 0 at every row (the column's shears still integrate to V),
// also on unequal boxes; the point correction's mean across z (Simpson) is 0 too.
TEST(FlexureShear, AgentMeansIntegrateExactly) {
  const double h = 0.02, d = 0.04, nu = 0.3, scale = kV / (h * d);
  const std::vector<double> ys{-0.01, -0.006, -0.0025, 0.001, 0.005, 0.01};
  const std::vector<double> zs{-0.02, -0.017, -0.01, -0.002, 0.0, 0.009, 0.0155, 0.02};
  const auto means = flexure_correction_means(ys, zs, h, d, kV, nu);
  ASSERT_EQ(means.size(), 5u * 7u);
  const double gx[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  const double gw[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665, 0.2369268850561891};
  for (std::size_t j = 0; j < 5; ++j) {
    double row = 0;
    for (std::size_t m = 0; m < 7; ++m) {
      double at = 0, aw = 0;
      for (int p = 0; p < 5; ++p)
        for (int q = 0; q < 5; ++q) {
          const double y = 0.5 * (ys[j] + ys[j + 1]) + 0.5 * (ys[j + 1] - ys[j]) * gx[p];
          const double z = 0.5 * (zs[m] + zs[m + 1]) + 0.5 * (zs[m + 1] - zs[m]) * gx[q];
          const FlexureShear c = correction(y, z, h, d, nu);
          at += 0.25 * gw[p] * gw[q] * c.at, aw += 0.25 * gw[p] * gw[q] * c.aw;
        }
      EXPECT_NEAR(means[j * 7 + m].at, at, 2e-5 * scale) << j << " " << m;
      EXPECT_NEAR(means[j * 7 + m].aw, aw, 2e-5 * scale) << j << " " << m;
      row += means[j * 7 + m].at * (zs[m + 1] - zs[m]);
    }
    EXPECT_NEAR(row / d, 0.0, 1e-14 * scale) << j;
  }
  for (double y : {-0.007, 0.0, 0.0031}) {
    const int n = 400;
    double sum = 0;
    for (int i = 0; i <= n; ++i) sum += (i == 0 || i == n ? 1 : i % 2 ? 4 : 2) * correction(y, -0.5 * d + d * i / n, h, d, nu).at;
    EXPECT_NEAR(sum / (3 * n), 0.0, 1e-9 * scale) << y;
  }
}

// A section 1000 times deeper than wide: cosh(n pi h / d) overflows a double, the exp forms do not.
TEST(FlexureShear, DeepSectionStaysFinite) {
  const double h = 2.0, d = 0.002;
  const FlexureShear s = flexure_shear(0.9, 0.0007, h, d, kV, 0.3);
  EXPECT_TRUE(std::isfinite(s.at) && std::isfinite(s.aw));
  const auto means = flexure_correction_means({-1.0, 0.999, 1.0}, {-0.001, 0.0, 0.001}, h, d, kV, 0.3);
  for (const auto& m : means) EXPECT_TRUE(std::isfinite(m.at) && std::isfinite(m.aw));
  // Each half of the width holds the polynomial's mean, 0 (even in z, mean 0 across the width).
  EXPECT_NEAR(means[0].at, 0.0, 1e-12 * kV / (h * d));
  EXPECT_NEAR(means[1].at, 0.0, 1e-12 * kV / (h * d));
  EXPECT_NEAR(means[2].at, means[3].at, 1e-12 * kV / (h * d));
}
