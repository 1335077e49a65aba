// The directional rule set (the project's extension): hand-checked packet paths, exact load
// balance, mirror symmetry and a spread that grows linearly with depth.
#include <agent/directional.h>
#include <agent/load_transfer.h>

#include <gtest/gtest.h>

#include <cmath>

#include "../support/agent_fixtures.h"

using namespace agent;
using namespace test_support;  // plate, face, coefficients, kMaterial, the face directions

namespace {

const double kPi = std::acos(-1.0);

/// Two packets of equal weight with slopes -+0.3, no diffusion, on straight paths mirrored by the
/// free sides (the path law these hand-checked positions follow).
Coefficients two_packets() {
  Coefficients k;
  k.directional.paths = Paths::Mirror;
  k.gamma = 0;
  k.threshold = Threshold::Absolute;
  k.directional.directions = 2;
  k.directional.fan_angle = 2 * std::atan(0.3) * 180 / kPi;  // the angles are -+fan_angle / 2
  k.directional.fan_power = 0;
  k.directional.diffusion_length = 0;
  return k;
}

void expect_balanced(const Diagnostics& d) {
  EXPECT_EQ(d.lost, 0.0);
  EXPECT_NEAR(d.rigid_reaction + d.passed_out + d.dropped + d.lost, d.applied, 1e-12 * d.applied);
}

}  // namespace

TEST(Directional, TheFanHasNoStraightDownPacketAndItsWeightsSumToOne) {
  DirectionalCoefficients k;
  k.directions = 4;
  k.fan_angle = 60;
  k.fan_power = 2;
  const Fan fan = entry_fan(k, 2);
  // Angles -45, -15, 15, 45 degrees; weights cos^2: 0.5, 0.933, 0.933, 0.5 over 2.866.
  ASSERT_EQ(fan.slope.size(), 4u);
  EXPECT_NEAR(fan.slope[0], -1.0, 1e-15);
  EXPECT_NEAR(fan.slope[2], std::tan(kPi / 12), 1e-15);
  EXPECT_NEAR(fan.weight[0], 0.5 / (1 + 2 * std::pow(std::cos(kPi / 12), 2)), 1e-15);
  EXPECT_NEAR(fan.weight[0] + fan.weight[1] + fan.weight[2] + fan.weight[3], 1.0, 1e-15);
}

TEST(Directional, TwoPacketsByHandOneReflectedByAFreeSide) {
  // 1 N into the top-left agent of a 3 x 5 plate. Packet positions (agents from the left side),
  // row by row down: right 0.5, 0.8, 1.1, 1.4, 1.7 (agents 0 0 1 1 1); left 0.5, 0.2, -0.1
  // mirrored by the free side to 0.1 (now moving right), 0.4, 0.7 (agents 0 0 0 0 0).
  const Grid g = plate(3, 5);
  LoadTransfer m(g, kMaterial, two_packets(), RuleSet::Directional);
  m.solve({{g.index(0, 4, 0), direction(1, false), 1.0}});
  const double packets[5][3] = {{0.5, 0.5, 0}, {0.5, 0.5, 0}, {0.5, 0.5, 0}, {1, 0, 0}, {1, 0, 0}};  // rows 0..4
  // Rows 0-2 carry a moment 0.5 N x 1 agent about the load: the row's moment balance adds
  // -0.5 / sum (u - 1)^2 = -0.25 per agent from the row's middle, (+0.25, 0, -0.25).
  const double balance[5][3] = {{0.25, 0, -0.25}, {0.25, 0, -0.25}, {0.25, 0, -0.25}, {0, 0, 0}, {0, 0, 0}};
  for (int j = 0; j < 5; ++j)
    for (int i = 0; i < 3; ++i) {
      const double through = packets[j][i] + balance[j][i];
      EXPECT_NEAR(face(m, i, j, kPlusY), through, 1e-15) << i << "," << j;
      EXPECT_NEAR(face(m, i, j, kMinusY), through, 1e-15) << i << "," << j;  // passed on, or returned by the base
      // A packet along slope s loads the side faces with s^2 of its force.
      EXPECT_NEAR(face(m, i, j, kMinusX), 0.09 * packets[j][i], 1e-15);
      EXPECT_NEAR(face(m, i, j, kPlusX), 0.09 * packets[j][i], 1e-15);
    }
  EXPECT_NEAR(m.diagnostics().rigid_reaction, 1.0, 1e-15);
  EXPECT_EQ(m.generation()[g.index(1, 2, 0)], 3);  // two rows down, one across
  EXPECT_EQ(m.generation()[g.index(2, 2, 0)], -1);  // no packet: the moment balance alone
  EXPECT_EQ(m.diagnostics().packet_moves, 10u);
  expect_balanced(m.diagnostics());

  // A rigid left side absorbs the left packet instead, as a reaction.
  Grid walled = plate(3, 5);
  walled.set_boundary(walled.box_side(kMinusX), Boundary::Rigid);
  LoadTransfer w(walled, kMaterial, two_packets(), RuleSet::Directional);
  w.solve({{walled.index(0, 4, 0), direction(1, false), 1.0}});
  // Only the right packet goes on: 0.5 N one agent right of the load, balanced as above.
  EXPECT_NEAR(face(w, 0, 2, kPlusY), 0.25, 1e-15);
  EXPECT_NEAR(face(w, 1, 2, kPlusY), 0.5, 1e-15);
  EXPECT_NEAR(face(w, 2, 0, kMinusY), -0.25, 1e-15);
  EXPECT_NEAR(w.diagnostics().rigid_reaction, 1.0, 1e-15);
  expect_balanced(w.diagnostics());
}

TEST(Directional, LoadBalanceIsExactIn2DAnd3D) {
  for (int dim : {2, 3}) {
    Grid g = Grid::box(dim, {12, 10, dim == 3 ? 9 : 1}, Eigen::Vector3d(0.002, 0.002, 0.002), 0.002);
    g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
    g.make_air(g.index(3, 4, dim == 3 ? 2 : 0));  // a hole lets packets out through its free faces
    Coefficients k;  // the calibrated defaults
    k.directional.directions = dim == 3 ? 8 : 32;
    LoadTransfer m(g, kMaterial, k, RuleSet::Directional);
    const int kc = dim == 3 ? 4 : 0;
    m.solve({{g.index(4, 9, kc), direction(1, false), 1.5}, {g.index(10, 9, kc), direction(1, false), 0.5},
             {g.index(0, 5, kc), direction(0, true), 0.25}});  // one load from the side, along +x
    const auto& d = m.diagnostics();
    EXPECT_EQ(d.applied, 2.25);
    EXPECT_GT(d.rigid_reaction, 1.5) << dim;
    expect_balanced(d);
  }
}

TEST(Directional, ACentredLoadGivesMirrorSymmetricForces) {
  for (int dim : {2, 3}) {
    const int nz = dim == 3 ? 8 : 1;
    Grid g = Grid::box(dim, {20, 15, nz}, Eigen::Vector3d(0.002, 0.002, 0.002), 0.002);
    g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
    Coefficients k;
    k.directional.directions = dim == 3 ? 8 : 32;
    LoadTransfer m(g, kMaterial, k, RuleSet::Directional);
    std::vector<EntryLoad> loads;
    for (int i : {9, 10})
      for (int kz = dim == 3 ? 3 : 0; kz <= (dim == 3 ? 4 : 0); ++kz) loads.push_back({g.index(i, 14, kz), direction(1, false), 1.0});
    m.solve(loads);
    const int nd = 2 * dim;
    const auto& f = m.face_forces();
    double largest = 0;
    for (int kz = 0; kz < nz; ++kz)
      for (int j = 0; j < 15; ++j)
        for (int i = 0; i < 20; ++i) {
          const std::size_t c = g.index(i, j, kz), mirror_x = g.index(19 - i, j, kz);
          largest = std::max(largest, f[c * nd + kPlusY]);
          EXPECT_NEAR(f[c * nd + kPlusY], f[mirror_x * nd + kPlusY], 1e-12);
          EXPECT_NEAR(f[c * nd + kMinusX], f[mirror_x * nd + kPlusX], 1e-12);
          if (dim == 3) {
            EXPECT_NEAR(f[c * nd + kPlusY], f[g.index(i, j, nz - 1 - kz) * nd + kPlusY], 1e-12);
          }
        }
    EXPECT_GT(largest, 0.1);
  }
}

TEST(Directional, TheSpreadGrowsLinearlyWithDepth) {
  // Without diffusion each packet runs straight, so the load's width (the standard deviation of
  // the force across a row) is depth times the fan's slope deviation, plus the binning into
  // agents; with diffusion a random walk (width ~ sqrt(depth)) is added.
  const int w = 801, h = 200;
  Grid g = Grid::box(2, {w, h, 1}, Eigen::Vector3d(1, 1, 1), 1.0);
  g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  Coefficients k;
  k.directional.paths = Paths::Mirror;  // straight rays (turning paths turn: not linear by design)
  k.directional.diffusion_length = 0;
  k.directional.fan_angle = 60;  // keeps the fan inside the plate down to the base
  const Fan fan = entry_fan(k.directional, 2);
  double slope_variance = 0;
  for (std::size_t i = 0; i < fan.slope.size(); ++i) slope_variance += fan.weight[i] * fan.slope[i] * fan.slope[i];
  LoadTransfer m(g, kMaterial, k, RuleSet::Directional);
  m.solve({{g.index(w / 2, h - 1, 0), direction(1, false), 1.0}});
  auto width = [&](int depth) {
    double sum = 0, second = 0;
    for (int i = 0; i < w; ++i) {
      const double f = face(m, i, h - 1 - depth, kPlusY);
      sum += f;
      second += f * (i - w / 2) * (i - w / 2);
    }
    EXPECT_NEAR(sum, 1.0, 1e-12);
    return std::sqrt(second / sum);
  };
  for (int depth : {40, 80, 160}) EXPECT_NEAR(width(depth), depth * std::sqrt(slope_variance), 0.01 * depth) << depth;
  EXPECT_NEAR(width(160) / width(40), 4.0, 0.05);  // linear; a random walk would give 2
}

TEST(Directional, RejectsAnOddFanAndCoefficientsOutOfRange) {
  const Grid g = plate(4, 4);
  auto with = [](auto set) {
    Coefficients k;
    set(k.directional);
    return k;
  };
  EXPECT_THROW(LoadTransfer(g, kMaterial, with([](auto& d) { d.directions = 31; }), RuleSet::Directional),
               std::invalid_argument);
  EXPECT_THROW(LoadTransfer(g, kMaterial, with([](auto& d) { d.fan_angle = 90; }), RuleSet::Directional),
               std::invalid_argument);
  EXPECT_THROW(LoadTransfer(g, kMaterial, with([](auto& d) { d.diffusion_length = -1; }), RuleSet::Directional),
               std::invalid_argument);
  // The seed's rule sets do not read the directional coefficients.
  EXPECT_NO_THROW(LoadTransfer(g, kMaterial, with([](auto& d) { d.directions = 31; }), RuleSet::Conserving));
}
