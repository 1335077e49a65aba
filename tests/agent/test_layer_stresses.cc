// The layer solver of the 3D directional stresses (agent/layer_stresses.h): a layer's in-plane
// stresses of least complementary energy, against closed forms.
#include <agent/layer_stresses.h>

#include <gtest/gtest.h>

#include <cmath>

namespace {

using agent::LayerBox;
using agent::LayerFields;
using agent::LayerSolver;

constexpr double kNu = 0.3;

LayerBox square_box(int n, double h) {
  LayerBox box{n, n, h, h, std::vector<char>(std::size_t(n) * std::size_t(n), 1)};
  return box;
}

LayerFields empty_fields(const LayerBox& box) {
  const std::size_t m = box.solid.size();
  return {std::vector<double>(m), std::vector<double>(m), std::vector<double>(m), {}, {}, {}};
}

double largest(const LayerFields& f) {
  double m = 0;
  for (std::size_t c = 0; c < f.sigma0.size(); ++c)
    m = std::max({m, std::abs(f.sigma0[c]), std::abs(f.sigma1[c]), std::abs(f.tau01[c])});
  return m;
}

// A uniform sigma_normal only asks the free layer for a uniform Poisson strain: it takes it without
// stress, holes and all.
TEST(LayerStresses, AUniformNormalStressLeavesAFreeLayerUnstressed) {
  LayerBox box = square_box(12, 1e-3);
  box.solid[5 + 12 * 5] = box.solid[6 + 12 * 5] = box.solid[5 + 12 * 6] = 0;  // a hole
  LayerFields f = empty_fields(box);
  for (std::size_t c = 0; c < f.normal.size(); ++c) f.normal[c] = box.solid[c] ? -4000.0 : 0.0;
  LayerSolver(kNu).solve(box, f);
  EXPECT_LT(largest(f), 1e-9 * 4000);
}

// Eshelby's circular inclusion in plane stress, in a free disk: a disk of radius a whose agents
// carry sigma_normal = s wants the strain -nu s / E. In an infinite plate it is held to
// sigma_rr = sigma_tt = nu s / 2 inside and sigma_rr = -sigma_tt = nu s / 2 (a / r)^2 outside;
// the free rim at R adds the uniform -nu s / 2 (a / R)^2 to both. Radii: the voxel disks' areas'.
TEST(LayerStresses, ADiskOfNormalStressIsEshelbysInclusion) {
  const int n = 101, centre = 50;
  const double h = 1e-3, s = -1e4;
  LayerBox box = square_box(n, h);
  LayerFields f = empty_fields(box);
  double inner = 0, outer = 0;
  for (int i1 = 0; i1 < n; ++i1)
    for (int i0 = 0; i0 < n; ++i0) {
      const std::size_t c = std::size_t(i0 + n * i1);
      const double r = std::hypot(i0 - centre, i1 - centre);
      box.solid[c] = r < 50;
      outer += box.solid[c];
      if (r < 10.5) {
        f.normal[c] = s;
        inner += 1;
      }
    }
  LayerSolver(kNu).solve(box, f);
  const double kPi = 3.14159265358979323846, a2 = inner / kPi, rim = kNu * s / 2 * a2 / (outer / kPi);
  const std::size_t mid = std::size_t(centre + n * centre);
  EXPECT_NEAR(f.sigma0[mid], kNu * s / 2 - rim, 0.01 * std::abs(kNu * s / 2));
  EXPECT_NEAR(f.sigma1[mid], kNu * s / 2 - rim, 0.01 * std::abs(kNu * s / 2));
  EXPECT_NEAR(f.tau01[mid], 0, 1e-9 * std::abs(s));
  const int r = 21;  // on the axis through the centre along 0: sigma_rr = sigma0, sigma_tt = sigma1
  const std::size_t out = std::size_t(centre + r + n * centre);
  const double outside = kNu * s / 2 * a2 / (r * r);
  EXPECT_NEAR(f.sigma0[out], outside - rim, 0.03 * std::abs(outside));
  EXPECT_NEAR(f.sigma1[out], -outside - rim, 0.03 * std::abs(outside));
}

// A body force a rigid motion would take (a net force, a net moment) is the shears' imbalance: it is
// taken out per piece, so two pieces pushed apart and a piece turned as a whole carry nothing.
TEST(LayerStresses, WhatARigidMotionWouldTakeIsTakenOutPerPiece) {
  LayerBox box = square_box(10, 2e-3);
  for (int i1 = 0; i1 < 10; ++i1) box.solid[std::size_t(4 + 10 * i1)] = box.solid[std::size_t(5 + 10 * i1)] = 0;
  LayerFields f = empty_fields(box);
  for (int i1 = 0; i1 < 10; ++i1)
    for (int i0 = 0; i0 < 10; ++i0) {
      const std::size_t c = std::size_t(i0 + 10 * i1);
      if (!box.solid[c]) continue;
      f.body0[c] = i0 < 4 ? -3e6 : 5e6;  // each piece pushed as a whole
      f.body1[c] = i0 < 4 ? 1e6 * (i0 - 1.5) : 0.0;  // the left piece turned about its centre
      f.body0[c] += i0 < 4 ? -1e6 * (i1 - 4.5) : 0.0;
    }
  LayerSolver(kNu).solve(box, f);
  EXPECT_LT(largest(f), 1e-9 * 5e6 * 2e-3 * 10);
}

// Agents joined only at corners are one piece with hinges: a chain of three turned about its
// hinges is a motion without strain that no rigid motion of the piece takes out, and the body
// force below (after the piece's net force and moment are taken out) only turns them. The shift
// keeps the solve finite; each agent, free to turn and to take its Poisson strain, carries nothing
// (to 1e-6 of the load's scale F h + |sigma_normal|, not 1 / shift).
TEST(LayerStresses, AgentsJoinedAtCornersStayFiniteWhenTheLoadTurnsTheHinges) {
  LayerBox box = square_box(3, 1e-3);
  box.solid = {1, 0, 0, 0, 1, 0, 0, 0, 1};  // cells (0, 0), (1, 1), (2, 2)
  LayerFields f = empty_fields(box);
  const double force = 1e6;
  f.body0 = {force, 0, 0, 0, 0, 0, 0, 0, -force};
  f.body1 = {-force, 0, 0, 0, 0, 0, 0, 0, force};
  f.normal = {-1e3, 0, 0, 0, 2e3, 0, 0, 0, -1e3};
  LayerSolver(kNu).solve(box, f);
  for (std::size_t c = 0; c < 9; ++c)
    EXPECT_TRUE(std::isfinite(f.sigma0[c]) && std::isfinite(f.sigma1[c]) && std::isfinite(f.tau01[c])) << c;
  EXPECT_LT(largest(f), 1e-6 * (force * 1e-3 + 2e3));
}

// A layer with the same cells reuses the factorisation: the answer is a fresh solver's to the bit.
TEST(LayerStresses, ALayerLikeThePreviousReusesItsFactorisation) {
  const LayerBox box = square_box(8, 1e-3);
  LayerFields first = empty_fields(box), again = empty_fields(box), fresh = empty_fields(box);
  for (std::size_t c = 0; c < first.normal.size(); ++c) {
    first.normal[c] = -100.0 * double(c % 7);
    again.normal[c] = fresh.normal[c] = 50.0 * double(c % 5);
    again.body0[c] = fresh.body0[c] = 1e5 * double(c % 3);
  }
  LayerSolver solver(kNu);
  solver.solve(box, first);
  solver.solve(box, again);
  LayerSolver(kNu).solve(box, fresh);
  EXPECT_EQ(again.sigma0, fresh.sigma0);
  EXPECT_EQ(again.sigma1, fresh.sigma1);
  EXPECT_EQ(again.tau01, fresh.tau01);
  EXPECT_GT(largest(fresh), 1.0);
}

}  // namespace
