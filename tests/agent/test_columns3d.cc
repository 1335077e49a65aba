// The column rule set in 3D (agent/columns.h): a prism of cube agents clamped at one end or on two
// supports. Hand statics per column, Navier over the section (I = b h^3 / 12), Jourawski per level
// (b(t) the section's width there: a notch changes it), the tip deflection of Euler-Bernoulli with
// Timoshenko's shear, the 2D beam of the same section (thickness = width), symmetry across w, a
// load along the other lateral axis, and what 3D refuses.
#include <agent/columns.h>
#include <agent/fields.h>
#include <agent/load_transfer.h>

#include <gtest/gtest.h>

#include <cmath>

#include "../support/agent_fixtures.h"
#include "../support/column_refusal.h"

using namespace agent;
using test_support::column_refusal;
using test_support::kMinusX, test_support::kMinusY;

namespace {

const Material kSteel{206e9, 0.3};
constexpr double kH = 5e-3;  // agent edge [m]
constexpr int kMinusZ = 4;
constexpr double kTol = 1e-19;  // [m]: 1e-12 of the tip's deflection (0.24 um)
const double kG = kSteel.young / (2 * (1 + kSteel.poisson));

/// 100 x 20 x 20 mm of 5 mm cubes (20 x 4 x 4), clamped at x = 0 (its -x side rigid).
Grid cantilever3d() {
  Grid g = Grid::box(3, {20, 4, 4}, Eigen::Vector3d(kH, kH, kH));
  g.set_boundary(g.box_side(kMinusX), Boundary::Rigid);
  return g;
}

/// `force` N along `dir`, shared equally by the agents of column i on the face opposite to `dir`
/// (a downward load on the top face: the agents j = top, every k).
std::vector<EntryLoad> on_face(const Grid& g, int i, int dir, double force) {
  const int t = axis_of(dir), w = 3 - 0 - t, top = is_positive(dir) ? 0 : g.cells[t] - 1;
  std::vector<EntryLoad> loads;
  for (int k = 0; k < g.cells[w]; ++k) {
    std::array<int, 3> c{i, 0, 0};
    c[t] = top, c[w] = k;
    loads.push_back({g.index(c[0], c[1], c[2]), dir, force / g.cells[w]});
  }
  return loads;
}

LoadTransfer solved(const Grid& g, const std::vector<EntryLoad>& loads) {
  LoadTransfer m(g, kSteel, Coefficients{}, RuleSet::Columns);
  m.solve(loads);
  return m;
}

double u(const LoadTransfer& m, int i, int j, int k, int axis) {
  return m.displacement()[m.grid().node_index(i, j, k) * 3 + std::size_t(axis)];
}

}  // namespace

// The clamp takes the load and its couple; every column carries v = -P and m = P (x_l - x) (the
// part of the body below it: the clamp's force and couple), the loaded column half the force.
// Nothing is lost.
TEST(Columns3D, CantileverStaticsAndReactions) {
  const Grid g = cantilever3d();
  const double P = 2, xl = 0.0975;
  const auto c = column_statics(g, on_face(g, 19, kMinusY, P));
  EXPECT_EQ(c.plan.axis, 0);
  EXPECT_EQ(c.plan.across, 1);
  EXPECT_EQ(c.plan.width_axis(), 2);
  EXPECT_EQ(c.plan.holding, Holding::Clamp);
  EXPECT_DOUBLE_EQ(c.reactions[0], P);
  EXPECT_NEAR(c.clamp_moment, P * xl, 1e-15);
  for (int i = 0; i < 19; ++i) {
    EXPECT_NEAR(c.v[std::size_t(i)], -P, 1e-14) << i;
    EXPECT_NEAR(c.m[std::size_t(i)], P * (xl - (i + 0.5) * kH), 1e-14) << i;
  }
  EXPECT_NEAR(c.v[19], -P / 2, 1e-14);
  EXPECT_NEAR(c.m[19], 0.0, 1e-15);
  // The section: 20 x 20 mm, centroid at 10 mm along y and z, I = b h^3 / 12.
  for (std::size_t i = 0; i < 20; ++i) {
    EXPECT_NEAR(c.area[i], 4e-4, 1e-18);
    EXPECT_NEAR(c.centroid[i], 0.01, 1e-16);
    EXPECT_NEAR(c.centroid_w[i], 0.01, 1e-16);
    EXPECT_NEAR(c.inertia[i] / (0.02 * std::pow(0.02, 3) / 12), 1.0, 1e-12);
  }
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  EXPECT_DOUBLE_EQ(m.diagnostics().applied, P);
  EXPECT_DOUBLE_EQ(m.diagnostics().rigid_reaction, P);
  EXPECT_EQ(m.diagnostics().passed_out + m.diagnostics().dropped + m.diagnostics().lost, 0.0);
  EXPECT_EQ(m.diagnostics().agents_generated, 320u);
}

// Navier over the section: sigma_x = M (y - c) / I, the same across z (the outer fibres' M c / I,
// extrapolated from the agents' centres at 7.5 mm); Jourawski per level: tau_xy the parabola's mean
// over the level, the same across z, integrating over the section to v; tau_yz = tau_xz = 0;
// sigma_y and sigma_z the clamp's layer alone, nothing left 75 mm (28 l) from the clamp.
TEST(Columns3D, NavierAndJourawskiOverASection) {
  const Grid g = cantilever3d();
  const double P = 2, xl = 0.0975, I = std::pow(0.02, 4) / 12, A = 4e-4, dA = kH * kH;
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  const auto normal = agent_stresses(g, m.face_forces());
  const auto& tau = m.shear_stress();
  for (int i : {7, 15}) {  // beyond the clamp's layer's shears (the clamp's column: below)
    const double M = P * (xl - (i + 0.5) * kH);
    double v = 0;
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) {
        const std::size_t c = g.index(i, j, k);
        const double y = (j + 0.5) * kH - 0.01;
        EXPECT_NEAR(normal[c * 3], M * y / I, 1e-9 * M * 0.01 / I) << i << j << k;
        if (i == 15) {  // beyond the clamp's layer
          EXPECT_LT(std::abs(normal[c * 3 + 1]) + std::abs(normal[c * 3 + 2]), 1e-6 * std::abs(M * 0.01 / I));
        }
        const double mean = 1.5 * P / A * (1 - 4 * (y * y + kH * kH / 12) / (0.02 * 0.02));
        // (the clamp's shears' tail: its layer decays as exp(-x / 2.7 mm), 1e-3 of it at x = 19 mm)
        EXPECT_NEAR(tau[c * 3 + 0], -mean, 1e-6 * P / A) << i << j << k;
        EXPECT_EQ(tau[c * 3 + 1], 0.0);
        EXPECT_NEAR(tau[c * 3 + 2], 0.0, 1e-6 * P / A);
        v += tau[c * 3] * dA;
      }
    EXPECT_NEAR(v, -P, 1e-12) << i;
    // The top fibre (y = c = 10 mm): the top agents' stress extrapolated linearly.
    EXPECT_NEAR(normal[g.index(i, 3, 1) * 3] * 0.01 / 0.0075, M * 0.01 / I, 1e-9 * M * 0.01 / I);
    EXPECT_NEAR(normal[g.index(i, 0, 2) * 3] * 0.01 / 0.0075, -M * 0.01 / I, 1e-9 * M * 0.01 / I);
  }
}

TEST(Columns3D, TheClampsShearsKeepTheSectionsResultants) {
  // At the clamp the layer's sigma_y and sigma_z vary across the section; their shears by
  // equilibrium (tau_xz, and an addition to tau_xy) still integrate to the section's v = -P across
  // y and to 0 across z, tau_xz is odd in y and in z (sigma_z odd about the centroid, even across
  // the width) and the addition to tau_xy even in z, and they are not small there.
  const Grid g = cantilever3d();
  const double P = 2, A = 4e-4, dA = kH * kH;
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  const auto& tau = m.shear_stress();
  double v = 0, across = 0, largest = 0;
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k) {
      const std::size_t c = g.index(0, j, k);
      v += tau[c * 3] * dA, across += tau[c * 3 + 2] * dA;
      largest = std::max(largest, std::abs(tau[c * 3 + 2]));
      EXPECT_NEAR(tau[g.index(0, 3 - j, k) * 3 + 2], -tau[c * 3 + 2], 1e-9 * P / A) << j << k;
      EXPECT_NEAR(tau[g.index(0, j, 3 - k) * 3 + 2], -tau[c * 3 + 2], 1e-9 * P / A) << j << k;
      EXPECT_NEAR(tau[g.index(0, j, 3 - k) * 3], tau[c * 3], 1e-9 * P / A) << j << k;
      EXPECT_EQ(tau[g.index(19, j, k) * 3 + 2], 0.0);  // the free end
    }
  EXPECT_NEAR(v, -P, 1e-12);
  EXPECT_NEAR(across, 0.0, 1e-12);
  EXPECT_GT(largest, 0.5 * P / A);
}

// The deflection of the centre line (y = z = 10 mm) at x = 95 mm: Euler-Bernoulli's P x^2 (3 x_l -
// x) / (6 E I) plus Timoshenko's P x / (k G A), k = 5/6 (Jourawski's parabola, uniform across z).
TEST(Columns3D, CantileverDeflectionIsBeamTheorys) {
  const Grid g = cantilever3d();
  const double P = 2, xl = 0.0975, x = 0.095, I = std::pow(0.02, 4) / 12, A = 4e-4;
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  const double expected = -(P * x * x * (3 * xl - x) / (6 * kSteel.young * I) + P * x / (5.0 / 6 * kG * A));
  EXPECT_NEAR(u(m, 19, 2, 2, 1) / expected, 1.0, 2e-3);
  // The clamp holds its section's centre: no axial displacement anywhere on its plane, no deflection
  // or lateral displacement at its centre.
  for (int j = 0; j <= 4; ++j)
    for (int k = 0; k <= 4; ++k) EXPECT_EQ(u(m, 0, j, k, 0), 0.0);
  EXPECT_EQ(u(m, 0, 2, 2, 1), 0.0);
  EXPECT_NEAR(u(m, 0, 2, 2, 2), 0.0, 1e-30);  // the centroid along z, rounded
  for (int i = 1; i <= 20; ++i) EXPECT_LT(u(m, i, 2, 2, 1), u(m, i - 1, 2, 2, 1));
}

// The 2D beam of the same section (20 mm deep, 20 mm thick) and the same load: the same u_x at
// every node, the same deflection on the centre plane z = 10 mm (the anticlastic part is zero
// there), the same tau_xy beyond the clamp's shears.
TEST(Columns3D, SameAsThe2DBeamOfTheSameSection) {
  const Grid g3 = cantilever3d();
  Grid g2 = Grid::box(2, {20, 4, 1}, Eigen::Vector3d(kH, kH, kH), 0.02);
  g2.set_boundary(g2.box_side(kMinusX), Boundary::Rigid);
  const double P = 2;
  const auto m3 = solved(g3, on_face(g3, 19, kMinusY, P));
  const auto m2 = solved(g2, {{g2.index(19, 3, 0), kMinusY, P}});
  const double scale = std::abs(m2.displacement()[g2.node_index(20, 2, 0) * 2 + 1]);
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 4; ++j) {
      const std::size_t n2 = g2.node_index(i, j, 0) * 2;
      for (int k = 0; k <= 4; ++k) ASSERT_NEAR(u(m3, i, j, k, 0), m2.displacement()[n2], 1e-12 * scale) << i << j << k;
      ASSERT_NEAR(u(m3, i, j, 2, 1), m2.displacement()[n2 + 1], 1e-12 * scale) << i << j;
    }
  // tau_xy beyond the clamp's shears (3D only: the 2D beam has no clamp layer across the width;
  // their tail is below 1e-6 of P / A from x = 25 mm)
  for (int i = 10; i < 20; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k)
        ASSERT_NEAR(m3.shear_stress()[g3.index(i, j, k) * 3], m2.shear_stress()[g2.index(i, j, 0)], 1e-6 * P / 4e-4) << i << j << k;
}

// Symmetric across z (the section and the load are): sigma_x, tau_xy, u_x and u_y even in z - z_c,
// u_z odd; u_z is the Poisson strain -nu sigma_x / E integrated from the centre plane, and u_y's
// anticlastic part +nu M / (2 E I) (z - z_c)^2.
TEST(Columns3D, SymmetricAcrossTheWidthAndAnticlastic) {
  const Grid g = cantilever3d();
  const double P = 2, xl = 0.0975, I = std::pow(0.02, 4) / 12, E = kSteel.young, nu = kSteel.poisson;
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 4; ++k) {
        EXPECT_EQ(u(m, i, j, k, 0), u(m, i, j, 4 - k, 0));
        EXPECT_NEAR(u(m, i, j, k, 1), u(m, i, j, 4 - k, 1), kTol);
        EXPECT_NEAR(u(m, i, j, k, 2), -u(m, i, j, 4 - k, 2), kTol);
      }
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) EXPECT_EQ(m.shear_stress()[g.index(i, j, k) * 3], m.shear_stress()[g.index(i, j, 3 - k) * 3]);
  // Inside column 10 (node line 10 is shared by columns 9 and 10: the mean of their moments).
  const double M = P * (xl - 0.5 * (0.0475 + 0.0525));
  const double uz = -nu / E * M * (0.02 - 0.01) / I * (0.0 - 0.01);  // the top, z = 0
  EXPECT_NEAR(u(m, 10, 4, 0, 2), uz, 1e-9 * std::abs(uz));
  EXPECT_NEAR(u(m, 10, 2, 0, 1) - u(m, 10, 2, 2, 1), nu * M / (2 * E * I) * 1e-4, 1e-9 * std::abs(uz));
}

// A load along z (the other lateral axis) bends the same beam about y: its fields are the -y
// load's with y and z swapped.
TEST(Columns3D, LoadAlongTheOtherLateralAxis) {
  const Grid g = cantilever3d();
  const auto y = solved(g, on_face(g, 19, kMinusY, 2.0)), z = solved(g, on_face(g, 19, kMinusZ, 2.0));
  const auto plan = plan_columns(g, on_face(g, 19, kMinusZ, 2.0));
  EXPECT_EQ(plan.axis, 0);
  EXPECT_EQ(plan.across, 2);
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 4; ++j)
      for (int k = 0; k <= 4; ++k) {
        ASSERT_NEAR(u(z, i, j, k, 0), u(y, i, k, j, 0), kTol) << i << j << k;
        ASSERT_NEAR(u(z, i, j, k, 2), u(y, i, k, j, 1), kTol) << i << j << k;
        ASSERT_NEAR(u(z, i, j, k, 1), u(y, i, k, j, 2), kTol) << i << j << k;
      }
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 4; ++k) ASSERT_NEAR(z.shear_stress()[g.index(i, j, k) * 3 + 2], y.shear_stress()[g.index(i, k, j) * 3], 1e-9);
}

// A notch (the top level of column 10 half as wide: two of its four agents air): the section's
// centroid drops, its width at the top level is 10 mm, and Jourawski's shear there is v Q / (I b)
// with Q of that level alone (b cancels: v / I times the mean of (z1^2 - z^2) / 2); the section's
// shears still integrate to v.
TEST(Columns3D, NotchChangesTheWidthOfItsLevel) {
  Grid g = cantilever3d();
  g.make_air(g.index(10, 3, 0)), g.make_air(g.index(10, 3, 1));
  const double P = 2;
  const auto c = column_statics(g, on_face(g, 19, kMinusY, P));
  const double rc = (4 * (2.5 + 7.5 + 12.5) + 2 * 17.5) * 1e-3 / 14;
  EXPECT_NEAR(c.centroid[10], rc, 1e-15);
  EXPECT_NEAR(c.centroid_w[10], (12 * 0.01 + 0.0125 + 0.0175) / 14, 1e-15);
  const auto m = solved(g, on_face(g, 19, kMinusY, P));
  const double z1 = 0.02 - rc, z0 = 0.015 - rc, I = c.inertia[10];
  const double expected = c.v[10] / I * (0.5 * z1 * z1 - (z1 * z1 * z1 - z0 * z0 * z0) / (6 * kH));
  EXPECT_NEAR(m.shear_stress()[g.index(10, 3, 2) * 3], expected, 1e-9 * std::abs(expected));
  EXPECT_NEAR(m.shear_stress()[g.index(10, 3, 3) * 3], expected, 1e-9 * std::abs(expected));
  double v = 0;
  for (int j = 0; j < 4; ++j)
    for (int k = 0; k < 4; ++k)
      if (!g.is_air(g.index(10, j, k))) v += m.shear_stress()[g.index(10, j, k) * 3] * kH * kH;
  // (to the clamp's shears' tail: a line along x through the notch's air drops what it carried)
  EXPECT_NEAR(v, -P, 1e-10);
}

// On two supports (the bottom faces of the first and last columns, across the whole width): the
// beam axis is the one the supports lie apart along; free to slide, the midspan deflects as
// Euler-Bernoulli with Timoshenko's shear, P x (3 L^2 - 4 x^2) / (48 E I) + P x / (2 k G A).
TEST(Columns3D, SimplySupportedBeam) {
  Grid g = Grid::box(3, {41, 4, 4}, Eigen::Vector3d(kH, kH, kH));
  std::vector<BoundaryFace> faces;
  for (int k = 0; k < 4; ++k) faces.push_back({g.index(0, 0, k), kMinusY}), faces.push_back({g.index(40, 0, k), kMinusY});
  g.set_boundary(faces, Boundary::Rigid);
  const double P = 2, L = 0.2, I = std::pow(0.02, 4) / 12, A = 4e-4;
  const auto loads = on_face(g, 20, kMinusY, P);
  const auto c = column_statics(g, loads);
  EXPECT_EQ(c.plan.holding, Holding::Supports);
  EXPECT_EQ(c.plan.axis, 0);
  EXPECT_NEAR(c.reactions[0], P / 2, 1e-14);
  EXPECT_NEAR(c.reactions[1], P / 2, 1e-14);
  TransferResults free;
  free.faces.assign(g.count() * 6, 0), free.generation.assign(g.count(), -1), free.shear.assign(g.count() * 3, 0);
  column_fields(g, kSteel, c, loads, free);
  const double x = 0.0975;
  const double expected = -(P * x * (3 * L * L - 4 * x * x) / (48 * kSteel.young * I) + P * x / (2 * 5.0 / 6 * kG * A));
  const double mid = 0.5 * (free.displacement[g.node_index(20, 0, 2) * 3 + 1] + free.displacement[g.node_index(21, 0, 2) * 3 + 1]);
  EXPECT_NEAR(mid / expected, 1.0, 2e-3);
  const auto bonded = solved(g, loads);  // the bonded supports' thrust holds the bottom fibre
  const auto& ub = bonded.displacement();
  EXPECT_NEAR(ub[g.node_index(40, 0, 2) * 3] - ub[g.node_index(1, 0, 2) * 3], 0.0, 1e-9 * std::abs(expected));
}

// The same prism on tiles: every stress and displacement the dense grid's.
TEST(Columns3D, TiledGridGivesTheDenseFields) {
  Grid dense = cantilever3d();
  dense.make_air(dense.index(10, 3, 0));
  const Grid tiled = tile(dense);
  ASSERT_TRUE(tiled.tiled());
  const auto a = solved(dense, on_face(dense, 19, kMinusY, 2.0)), b = solved(tiled, on_face(tiled, 19, kMinusY, 2.0));
  for (int k = 0; k < 4; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 20; ++i) {
        const std::size_t c = dense.index(i, j, k), d = tiled.index(i, j, k);
        ASSERT_EQ(a.shear_stress()[c * 3], b.shear_stress()[d * 3]);
        ASSERT_EQ(a.face_forces()[c * 6], b.face_forces()[d * 6]);
      }
  for (int k = 0; k <= 4; ++k)
    for (int j = 0; j <= 4; ++j)
      for (int i = 0; i <= 20; ++i)
        for (int x = 0; x < 3; ++x)
          ASSERT_EQ(a.displacement()[dense.node_index(i, j, k) * 3 + x], b.displacement()[tiled.node_index(i, j, k) * 3 + x]);
}

// What 3D cannot carry is said in one sentence.
TEST(Columns3D, RefusesWhatItCannotCarry) {
  const Grid g = cantilever3d();
  auto both = on_face(g, 19, kMinusY, 1.0);
  both.push_back({g.index(19, 1, 3), kMinusZ, 1.0});
  EXPECT_NE(column_refusal(g, both).find("loads along both y and z"), std::string::npos) << column_refusal(g, both);
  Grid two = cantilever3d();
  two.set_boundary(two.box_side(kMinusZ), Boundary::Rigid);
  EXPECT_NE(column_refusal(two, on_face(two, 19, kMinusY, 1.0)).find("rigid faces across both x and z"), std::string::npos);
  // Four corner supports under a plate: apart along x and z.
  Grid plate = Grid::box(3, {10, 2, 10}, Eigen::Vector3d(kH, kH, kH));
  plate.set_boundary({{plate.index(0, 0, 0), kMinusY}, {plate.index(9, 0, 0), kMinusY}, {plate.index(0, 0, 9), kMinusY},
                      {plate.index(9, 0, 9), kMinusY}},
                     Boundary::Rigid);
  EXPECT_NE(column_refusal(plate, {{plate.index(5, 1, 5), kMinusY, 1.0}}).find("apart along both x and z"), std::string::npos);
  // A block on its base: one support (the marching rule sets carry it).
  Grid block = Grid::box(3, {4, 4, 4}, Eigen::Vector3d(kH, kH, kH));
  block.set_boundary(block.box_side(kMinusY), Boundary::Rigid);
  EXPECT_NE(column_refusal(block, {{block.index(2, 3, 2), kMinusY, 1.0}}).find("form one support"), std::string::npos);
  EXPECT_NE(column_refusal(Grid::box(3, {4, 4, 4}, Eigen::Vector3d(kH, kH, kH)), {{block.index(2, 3, 2), kMinusY, 1.0}}).find("no rigid face"),
            std::string::npos);
  // A load along the beam axis (the clamp's normal): the clamp lies ahead of it.
  EXPECT_NE(column_refusal(g, {{g.index(19, 2, 2), kMinusX, 1.0}}).find("form one support"), std::string::npos);
}
