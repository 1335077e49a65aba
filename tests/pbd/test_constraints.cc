// The angle and distance constraints: formulas against finite differences and the seed's form,
// projections that satisfy the constraint and conserve momentum, no NaN at 180 degrees.
#include "seed_correction.h"

#include <pbd/constraints.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using pbd::Vec3;

namespace {

const double kPi = std::acos(-1.0);

Vec3 random_vec(std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  return Vec3(u(rng), u(rng), u(rng));
}

/// C as a plain function of the positions (what the gradient must differentiate).
double C_of(const Vec3& p1, const Vec3& p2, const Vec3& p3, double theta0, const Vec3* axis) {
  double t = axis ? pbd::signed_angle(p1, p2, p3, *axis) : pbd::angle(p1, p2, p3);
  double c = t - theta0;
  while (c > kPi) c -= 2 * kPi;
  while (c <= -kPi) c += 2 * kPi;
  return c;
}

void expect_gradient_matches_fd(const Vec3& p1, const Vec3& p2, const Vec3& p3, double theta0, const Vec3* axis) {
  const auto g = pbd::angle_constraint_gradient(p1, p2, p3, theta0, axis);
  ASSERT_TRUE(g.valid);
  EXPECT_NEAR(g.C, C_of(p1, p2, p3, theta0, axis), 1e-12);
  const double eps = 1e-6;
  const Vec3* grads[3] = {&g.g1, &g.g2, &g.g3};
  for (int node = 0; node < 3; ++node)
    for (int a = 0; a < 3; ++a) {
      if (axis && std::abs((*axis)[a]) > 0.5) continue;  // the signed form lives in the plane
      Vec3 q[3] = {p1, p2, p3}, r[3] = {p1, p2, p3};
      q[node][a] += eps;
      r[node][a] -= eps;
      const double fd = (C_of(q[0], q[1], q[2], theta0, axis) - C_of(r[0], r[1], r[2], theta0, axis)) / (2 * eps);
      EXPECT_NEAR((*grads[node])[a], fd, 1e-6 * (1 + std::abs(fd))) << "node " << node << " axis " << a;
    }
}

}  // namespace

TEST(PbdAngleConstraint, UnsignedGradientMatchesFiniteDifferences) {
  std::mt19937 rng(1);
  for (int t = 0; t < 50; ++t) {
    const Vec3 p1 = random_vec(rng), p2 = random_vec(rng), p3 = random_vec(rng);
    if (pbd::angle(p1, p2, p3) < 0.05 || pbd::angle(p1, p2, p3) > kPi - 0.05) continue;
    expect_gradient_matches_fd(p1, p2, p3, 1.0, nullptr);
  }
}

TEST(PbdAngleConstraint, SignedGradientMatchesFiniteDifferencesThroughStraight) {
  const Vec3 z = Vec3::UnitZ();
  // Through the straight state (theta = pi), on both sides, and far from it.
  for (double bend : {-0.3, -1e-3, 0.0, 1e-3, 0.3, 2.0}) {
    const Vec3 p3(0.1, 0.2, 0), p1 = p3 + Vec3(-0.7, 0, 0);
    const Vec3 p2 = p3 + 0.9 * Vec3(std::cos(bend), std::sin(bend), 0);
    expect_gradient_matches_fd(p1, p2, p3, kPi, &z);
    expect_gradient_matches_fd(p1, p2, p3, 2.5, &z);
  }
}

TEST(PbdAngleConstraint, GradientNormsAreInverseEdgeLengths) {
  std::mt19937 rng(2);
  for (int t = 0; t < 20; ++t) {
    const Vec3 p1 = random_vec(rng), p2 = random_vec(rng), p3 = random_vec(rng);
    const auto g = pbd::angle_constraint_gradient(p1, p2, p3, 0.5, nullptr);
    ASSERT_TRUE(g.valid);
    EXPECT_NEAR(g.g1.norm(), 1 / (p1 - p3).norm(), 1e-12 / (p1 - p3).norm());
    EXPECT_NEAR(g.g2.norm(), 1 / (p2 - p3).norm(), 1e-12 / (p2 - p3).norm());
  }
}

TEST(PbdAngleConstraint, RobustProjectionEqualsTheSeedsQForm) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> wu(0.5, 3.0);
  for (int t = 0; t < 30; ++t) {
    Vec3 p1 = random_vec(rng), p2 = random_vec(rng), p3 = random_vec(rng);
    const double theta0 = 0.3 + 2.5 * double(t) / 30;
    const double w1 = wu(rng), w2 = wu(rng), w3 = wu(rng);
    Vec3 d1, d2, d3;
    ASSERT_TRUE(pbd_test::seed_angle_correction(p1, p2, p3, w1, w2, w3, theta0, 1.0, d1, d2, d3));
    const Vec3 e1 = p1 + d1, e2 = p2 + d2, e3 = p3 + d3;
    double lambda = 0;
    pbd::project_angle(p1, p2, p3, w1, w2, w3, std::cos(theta0), std::sin(theta0), 0.0, lambda, nullptr);
    EXPECT_LT((p1 - e1).norm() + (p2 - e2).norm() + (p3 - e3).norm(), 1e-12);
  }
}

TEST(PbdAngleConstraint, ProjectionSatisfiesTheConstraint) {
  std::mt19937 rng(4);
  for (int t = 0; t < 30; ++t) {
    Vec3 p1 = random_vec(rng), p2 = random_vec(rng), p3 = random_vec(rng);
    const double theta0 = pbd::angle(p1, p2, p3) + 0.2 * (t % 2 ? 1 : -1);
    if (theta0 < 0.2 || theta0 > kPi - 0.2) continue;
    double lambda = 0;
    const double c0 = std::abs(pbd::angle(p1, p2, p3) - theta0);
    pbd::project_angle(p1, p2, p3, 1, 2, 3, std::cos(theta0), std::sin(theta0), 0.0, lambda, nullptr);
    EXPECT_LT(std::abs(pbd::angle(p1, p2, p3) - theta0), 0.1 * c0);  // one linearised step
    for (int k = 0; k < 6; ++k)
      pbd::project_angle(p1, p2, p3, 1, 2, 3, std::cos(theta0), std::sin(theta0), 0.0, lambda, nullptr);
    EXPECT_LT(std::abs(pbd::angle(p1, p2, p3) - theta0), 1e-12);
  }
}

TEST(PbdAngleConstraint, XpbdProjectionReachesTheCompliantBalance) {
  // Repeated XPBD iterations converge to C + alpha~ lambda = 0 (the compliant force balance).
  Vec3 p1(-1, 0.3, 0), p2(1, 0.2, 0), p3(0, 0, 0);
  const Vec3 z = Vec3::UnitZ();
  double lambda = 0;
  const double at = 0.7;
  for (int k = 0; k < 50; ++k) pbd::project_angle(p1, p2, p3, 1, 1, 1, -1, 0, at, lambda, &z);
  const double C = C_of(p1, p2, p3, kPi, &z);
  EXPECT_NEAR(C + at * lambda, 0.0, 1e-12);
  EXPECT_GT(std::abs(C), 1e-3);  // compliant: not driven to zero
}

TEST(PbdAngleConstraint, ProjectionConservesLinearAndAngularMomentum) {
  std::mt19937 rng(5);
  for (int t = 0; t < 20; ++t) {
    Vec3 p[3] = {random_vec(rng), random_vec(rng), random_vec(rng)};
    const Vec3 q[3] = {p[0], p[1], p[2]};
    const double w[3] = {0.5, 2.0, 1.3};
    double lambda = 0;
    pbd::project_angle(p[0], p[1], p[2], w[0], w[1], w[2], std::cos(1.0), std::sin(1.0), 0.1, lambda, nullptr);
    Vec3 lin = Vec3::Zero(), ang = Vec3::Zero();
    for (int j = 0; j < 3; ++j) {
      lin += (p[j] - q[j]) / w[j];
      ang += q[j].cross(p[j] - q[j]) / w[j];
    }
    EXPECT_LT(lin.norm(), 1e-14);
    EXPECT_LT(ang.norm(), 1e-12);  // first order: corrections are a linearised rotation-free step
  }
}

TEST(PbdAngleConstraint, StraightChainGivesNoNaN) {
  const Vec3 z = Vec3::UnitZ();
  for (double theta0 : {kPi, 2.5}) {
    for (const Vec3* axis : {(const Vec3*)nullptr, &z}) {
      Vec3 p1(-1, 0, 0), p2(2, 0, 0), p3(0, 0, 0);
      double lambda = 0;
      pbd::project_angle(p1, p2, p3, 1, 1, 1, std::cos(theta0), std::sin(theta0), 0.0, lambda, axis);
      EXPECT_TRUE(p1.allFinite() && p2.allFinite() && p3.allFinite());
      EXPECT_TRUE(std::isfinite(lambda));
      const auto g = pbd::angle_constraint_gradient(p1, p2, p3, theta0, axis);
      EXPECT_TRUE(std::isfinite(g.C));
      if (axis && theta0 != kPi) {
        EXPECT_TRUE(g.valid);
        EXPECT_NEAR(std::abs(pbd::signed_angle(p1, p2, p3, z)), theta0, 0.3);  // moved towards 2.5
      }
    }
  }
  // The seed's literal acos form has no answer there (sqrt(1 - d^2) = 0): it reports it.
  Vec3 d1, d2, d3;
  EXPECT_FALSE(pbd_test::seed_angle_correction(Vec3(-1, 0, 0), Vec3(2, 0, 0), Vec3::Zero(), 1, 1, 1, 2.5, 1, d1, d2, d3));
}

TEST(PbdDistanceConstraint, ProjectionRestoresTheLength) {
  Vec3 a(0, 0, 0), b(2, 1, 0);
  double lambda = 0;
  pbd::project_distance(a, b, 1.0, 3.0, 1.5, 0.0, lambda);
  EXPECT_NEAR((a - b).norm(), 1.5, 1e-14);
  EXPECT_LT(((a - Vec3(0, 0, 0)) / 1.0 + (b - Vec3(2, 1, 0)) / 3.0).norm(), 1e-14);
  // Coincident points: skipped, no NaN.
  Vec3 c(1, 1, 1), d(1, 1, 1);
  pbd::project_distance(c, d, 1, 1, 1, 0, lambda);
  EXPECT_TRUE(c.allFinite() && d.allFinite());
}

TEST(PbdAngleConstraint, ProjectionUsesTheExactDeviation) {
  // Small and large deviations (the fast small-angle atan path and std::atan2) give the exact
  // PBD step: C / sum w |grad C|^2 along the gradient.
  const Vec3 z = Vec3::UnitZ();
  for (double dev : {1e-9, 1e-4, 0.05, 0.0999, 0.3, 2.0}) {
    Vec3 p1(-1, 0, 0), p3(0, 0, 0), p2(std::cos(dev), std::sin(dev), 0);
    const auto g = pbd::angle_constraint_gradient(p1, p2, p3, kPi, &z);
    ASSERT_TRUE(g.valid);
    EXPECT_NEAR(std::abs(g.C), dev, 1e-15 * dev + 2e-16);  // sin(double(pi)) = 1.2e-16
    const double den = g.g1.squaredNorm() + g.g2.squaredNorm() + g.g3.squaredNorm();
    const Vec3 expect = p2 - g.C / den * g.g2;
    double lambda = 0;
    pbd::project_angle(p1, p2, p3, 1, 1, 1, -1, 0, 0.0, lambda, &z);
    EXPECT_LT((p2 - expect).norm(), 1e-15);
    EXPECT_NEAR(lambda, -g.C / den, 1e-15 * std::abs(g.C / den) + 1e-16);
  }
}
