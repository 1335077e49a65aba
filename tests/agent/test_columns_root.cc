// The column rule set at a clamp (agent/columns.h): the section spreads from the free end toward the
// clamp (an L-bracket's deeper root) at 45 degrees for the plane sections and as Flamant's fan for
// the stresses; the clamp's layer of sigma across the beam (Poisson's restraint by the bonded face,
// decaying as Papkovich-Fadle's end effect) and the loads' layer (a push on a face spreading into
// the section).
#include <agent/columns.h>
#include <agent/fields.h>
#include <agent/load_transfer.h>

#include <gtest/gtest.h>

#include <cmath>

#include "../support/agent_fixtures.h"

using namespace agent;
using test_support::kMinusX, test_support::kMinusY;

namespace {

const Material kSteel{206e9, 0.3};
constexpr double kH = 5e-3, kThick = 2e-3;

/// nx x ny agents of 5 mm, 2 mm thick, clamped at x = 0.
Grid cantilever(int nx, int ny) {
  Grid g = Grid::box(2, {nx, ny, 1}, Eigen::Vector3d(kH, kH, kH), kThick);
  g.set_boundary(g.box_side(kMinusX), Boundary::Rigid);
  return g;
}

/// An L clamped at its side: a foot of 20 x 4 agents, and above its first 4 columns an arm up to
/// 12 agents (the rest of the box air).
Grid l_bracket() {
  Grid g = cantilever(20, 12);
  for (int i = 4; i < 20; ++i)
    for (int j = 4; j < 12; ++j) g.make_air(g.index(i, j, 0));
  return g;
}

EntryLoad down(const Grid& g, int i, int top, double force) { return {g.index(i, top, 0), kMinusY, force}; }

LoadTransfer solved(const Grid& g, const std::vector<EntryLoad>& loads) {
  LoadTransfer m(g, kSteel, Coefficients{}, RuleSet::Columns);
  m.solve(loads);
  return m;
}

}  // namespace

// The foot's section is its 4 agents; toward the clamp the plane sections' section grows by one agent
// a column (45 degrees): columns 3, 2, 1, 0 hold rows 0-4, 0-5, 0-6, 0-7, and the arm's nodes above
// move as its top edge. The stresses' section is Flamant's fan: the foot's rows are its core, the
// arm's agents join it by d^4 / (d^2 + eta^2)^2, d the 45-degree reach (column 3: 1 agent, column 0:
// 4), eta the agent's height above the foot's top (column 0's top agent, 7.5 agents up: 1 / (1 +
// 1.875^2)^2 = 0.049042). Each column's stresses balance its resultants (sum sigma dA = 0, sum sigma
// (y - y_c) dA = m less the agents' own b h^3 / 12, about the weighted section's centroid; sum tau
// dA = v), the corner's shear changes sign across its height, and a uniform beam is untouched.
TEST(ColumnsRoot, SectionSpreadsFromTheFreeEndAsFlamantsFan) {
  const Grid g = l_bracket();
  const std::vector<EntryLoad> loads{down(g, 19, 3, 2.0)};
  Columns c = column_statics(g, loads);
  for (std::size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(c.first_row[i], 0) << i;
    EXPECT_EQ(c.last_row[i], i < 4 ? 7 - int(i) : 3) << i;
    EXPECT_TRUE(c.core_first[i] == 0 && c.core_last[i] == 3) << i;
    EXPECT_NEAR(c.reach_high[i], i < 4 ? 4.0 - double(i) : 0.0, 1e-12) << i;
    EXPECT_EQ(c.reach_low[i], 0.0) << i;
  }
  EXPECT_EQ(c.weight(0, 3), 1.0);
  EXPECT_NEAR(c.weight(0, 11), 0.0490416, 1e-7);
  EXPECT_NEAR(c.weight(0, 4), 0.9694675, 1e-7);  // eta = 0.5, d = 4: 1 / (1 + 0.125^2)^2
  EXPECT_NEAR(c.weight(3, 4), 0.64, 1e-15);       // eta = 0.5, d = 1: 1 / 1.25^2
  EXPECT_NEAR(c.centroid[0], 0.020, 1e-15);       // the plane sections' rows 0-7
  EXPECT_NEAR(c.inertia[0], kThick * std::pow(0.040, 3) / 12, 1e-20);
  EXPECT_NEAR(c.m[0], 2.0 * 0.095, 1e-15);  // the statics are the load's: P (x_l - x), x_l = 97.5 mm, x = 2.5 mm
  const auto m = solved(g, loads);
  const auto sigma = agent_stresses(g, m.face_forces());
  for (int i = 0; i < 20; ++i) {
    double area = 0, first = 0, second = 0;  // the fan's section (weights), by hand
    for (int j = 0; j < 12; ++j)
      if (!g.is_air(g.index(i, j, 0))) {
        const double share = c.weight(std::size_t(i), j), y = (j + 0.5) * kH;
        area += share * kH * kThick, first += share * y * kH * kThick, second += share * y * y * kH * kThick;
      }
    const double yc = first / area, own = area * kH * kH / 12, I = second - area * yc * yc + own;
    double n = 0, moment = 0, v = 0;
    for (int j = 0; j < 12; ++j) {
      const std::size_t cell = g.index(i, j, 0);
      if (g.is_air(cell)) continue;
      const double dA = kH * kThick, y = (j + 0.5) * kH;
      n += sigma[cell * 2] * dA, moment += sigma[cell * 2] * (y - yc) * dA, v += m.shear_stress()[cell] * dA;
    }
    EXPECT_NEAR(n, 0.0, 1e-12) << i;
    // Each agent holds its centre's sigma: the sum misses the agents' own share of I.
    EXPECT_NEAR(moment, c.m[std::size_t(i)] * (1 - own / I), 1e-12) << i;
    EXPECT_NEAR(v, i == 19 ? -1.0 : -2.0, 1e-12) << i;  // the loaded column: half the load
  }
  // Column 0's agents above its weighted centroid (18.9 mm), also beyond the 45-degree line, are in
  // tension; the corner column 2's shear changes sign across its height (the foot's rows against
  // the arm's: 0.16 MPa at row 1, -0.17 MPa at row 5).
  EXPECT_GT(sigma[g.index(0, 11, 0) * 2], 0.0);
  EXPECT_GT(sigma[g.index(0, 4, 0) * 2], 0.0);
  EXPECT_LT(m.shear_stress()[g.index(2, 1, 0)] * m.shear_stress()[g.index(2, 5, 0)], 0.0);
  // Column 0's plane section ends at node row 8: the nodes above it move as that edge.
  for (int k = 0; k < 2; ++k)
    for (int j = 9; j <= 12; ++j)
      EXPECT_EQ(m.displacement()[g.node_index(0, j, 0) * 2 + k], m.displacement()[g.node_index(0, 8, 0) * 2 + k]) << j;
  const Columns uniform = column_statics(cantilever(20, 6), {down(cantilever(20, 6), 19, 5, 1.0)});
  for (std::size_t i = 0; i < 20; ++i)
    EXPECT_TRUE(uniform.first_row[i] == 0 && uniform.last_row[i] == 5 && !uniform.widens(i) && uniform.weight(i, 5) == 1.0) << i;
}

// At the clamp the bonded face holds eps_y = 0: sigma_y = nu sigma_x (plane stress), decaying as
// exp(-d / l), l = H / 7.4977 (Papkovich-Fadle), faster near the free faces: l = (l0^-2 + f^-2)^-1/2,
// f the agent's distance to the nearer free face; each agent holds the decay's mean over its length.
// Odd about the centroid (as sigma_x); nothing between two supports.
TEST(ColumnsRoot, ClampLayerIsPoissonsRestraintDecaying) {
  const Grid g = cantilever(40, 8);
  const auto m = solved(g, {down(g, 39, 7, 2.0)});
  const auto sigma = agent_stresses(g, m.face_forces());
  const double l0 = 0.040 / 7.4977, nu = 0.3;
  for (int i : {0, 1, 2})
    for (int j : {0, 2, 3}) {
      const double f = (j + 0.5) * kH, l = 1 / std::sqrt(1 / (l0 * l0) + 1 / (f * f));
      const double mean = l / kH * (std::exp(-i * kH / l) - std::exp(-(i + 1) * kH / l));
      const std::size_t cell = g.index(i, j, 0), mirror = g.index(i, 7 - j, 0);
      EXPECT_NEAR(sigma[cell * 2 + 1], nu * mean * sigma[cell * 2], 1e-12 * std::abs(sigma[cell * 2])) << i << ", " << j;
      EXPECT_NEAR(sigma[mirror * 2 + 1], -sigma[cell * 2 + 1], 1e-9 * std::abs(sigma[cell * 2 + 1])) << i << ", " << j;
    }
  // At the clamp's column the layer is most of nu sigma_x inside (0.58 of it at the centroid's
  // agents: mean of exp over 5 mm with l = 4.9 mm), far from it nothing.
  EXPECT_GT(sigma[g.index(0, 3, 0) * 2 + 1] / sigma[g.index(0, 3, 0) * 2], 0.5 * nu);
  for (int j = 0; j < 8; ++j) EXPECT_LT(std::abs(sigma[g.index(25, j, 0) * 2 + 1]), 1e-9 * std::abs(sigma[g.index(25, 0, 0) * 2]));
  // The stress model: every component under a clamp.
  const auto model = ColumnTransfer::stress_model(g, Coefficients{}, {down(g, 39, 7, 2.0)});
  EXPECT_EQ(model.modelled, normal_stress_bits(2) | shear_bits(2));
  // Between two supports: no layer, sigma_y not modelled.
  Grid s = Grid::box(2, {41, 8, 1}, Eigen::Vector3d(kH, kH, kH), kThick);
  s.set_boundary({{s.index(0, 0, 0), kMinusY}, {s.index(40, 0, 0), kMinusY}}, Boundary::Rigid);
  const auto b = solved(s, {down(s, 20, 7, 2.0)});
  const auto sb = agent_stresses(s, b.face_forces());
  for (std::size_t cell = 0; cell < s.count(); ++cell) ASSERT_EQ(sb[cell * 2 + 1], 0.0) << cell;
  EXPECT_EQ(ColumnTransfer::stress_model(s, Coefficients{}, {down(s, 20, 7, 2.0)}).modelled, (normal_stress_bits(2) & ~2u) | shear_bits(2));
}

// In 3D the bonded clamp holds eps_y = eps_z = 0: on its plane sigma_y = sigma_z = nu / (1 - nu)
// sigma_x, each decaying over the section's extent along its own axis (a section 20 mm deep along
// y, 40 mm wide along z: l = 20 / 7.4977 and 40 / 7.4977 mm), faster near the faces across it.
TEST(ColumnsRoot, ClampLayerIn3DHoldsBothLateralStrains) {
  Grid g = Grid::box(3, {20, 4, 8}, Eigen::Vector3d(kH, kH, kH), 0.0);
  g.set_boundary(g.box_side(kMinusX), Boundary::Rigid);
  std::vector<EntryLoad> loads;
  for (int k = 0; k < 8; ++k) loads.push_back({g.index(19, 3, k), kMinusY, 0.25});
  const auto m = solved(g, loads);
  const auto sigma = agent_stresses(g, m.face_forces());
  const double ly = 0.020 / 7.4977, lz = 0.040 / 7.4977, ratio = 0.3 / 0.7;
  auto mean = [](double l0, double f, int i) {
    const double l = 1 / std::sqrt(1 / (l0 * l0) + 1 / (f * f));
    return l / kH * (std::exp(-i * kH / l) - std::exp(-(i + 1) * kH / l));
  };
  for (int i : {0, 1})
    for (int j : {0, 1})
      for (int k : {0, 3}) {
        const std::size_t c = g.index(i, j, k);
        const double sx = sigma[c * 3];
        EXPECT_NEAR(sigma[c * 3 + 1], ratio * mean(ly, (j + 0.5) * kH, i) * sx, 1e-12 * std::abs(sx)) << i << j << k;
        EXPECT_NEAR(sigma[c * 3 + 2], ratio * mean(lz, (k + 0.5) * kH, i) * sx, 1e-12 * std::abs(sx)) << i << j << k;
        // Odd about the centroid (y) and even across the width (z), as sigma_x.
        EXPECT_NEAR(sigma[g.index(i, 3 - j, k) * 3 + 1], -sigma[c * 3 + 1], 1e-9 * std::abs(sx));
        EXPECT_NEAR(sigma[g.index(i, j, 7 - k) * 3 + 2], sigma[c * 3 + 2], 1e-9 * std::abs(sx));
      }
  const auto model = ColumnTransfer::stress_model(g, Coefficients{}, loads);
  // tau_xy and the clamp's tau_xz; not tau_yz
  EXPECT_EQ(model.modelled, normal_stress_bits(3) | shear_bits(2) | (shear_bits(2) << unsigned(shear_pair(0, 2))));
}

// A push on the top face spreads into the section at 45 degrees and is passed to the shear over the
// depth: each row's sigma_y integrates to -P (2 - 3 e + e^3) / 4, e = 2 d / H - 1 (d the row's depth
// below the loaded face: P at the top, 0 on the free underside), at the tip (clipped by the free
// end) as in the middle of the span, where it is even about the load (to the clamp's layer's tail,
// 0.1 Pa of 1.3 kPa); a traction along a face (an
// inclined load's part along x on the top agents) has no such layer.
TEST(ColumnsRoot, LoadLayerSpreadsThePushOverTheDepth) {
  const Grid g = cantilever(40, 8);
  for (int i0 : {39, 20}) {
    const auto m = solved(g, {down(g, i0, 7, 2.0)});
    const auto sigma = agent_stresses(g, m.face_forces());
    for (int j = 0; j < 8; ++j) {
      double row = 0;
      for (int i = 10; i < 40; ++i) row += sigma[g.index(i, j, 0) * 2 + 1] * kH * kThick;  // beyond the clamp's layer
      const double e = 2 * ((8 - j - 0.5) * kH) / 0.04 - 1;  // the row's centre 0.5 - 7.5 agents below the top
      EXPECT_NEAR(row, -2.0 * (2 - 3 * e + e * e * e) / 4, 1e-4) << i0 << ", " << j;  // the clamp's layer's tail: 1e-5
      if (i0 == 20) {
        for (int k = 1; k < 8; ++k)
          EXPECT_NEAR(sigma[g.index(20 - k, j, 0) * 2 + 1], sigma[g.index(20 + k, j, 0) * 2 + 1], 0.1) << k << ", " << j;
      }
    }
  }
  // A plate 40 x 100 mm clamped at its base, 2 N along +x on a top agent: in the middle of the top
  // (an inclined load's part along the face: no face across x behind it) no layer, the top row's
  // sigma_x ~ 0 (the clamp's layer is gone 97.5 mm up, Navier's sigma_y is 0 at the loaded column);
  // on the corner agent (its -x face free: a push on it) the layer, 2 N over 7.5 mm x 2 mm there.
  Grid plate = Grid::box(2, {8, 20, 1}, Eigen::Vector3d(kH, kH, kH), kThick);
  plate.set_boundary(plate.box_side(kMinusY), Boundary::Rigid);
  const auto along = agent_stresses(plate, solved(plate, {{plate.index(4, 19, 0), test_support::kPlusX, 2.0}}).face_forces());
  for (int i = 0; i < 8; ++i) EXPECT_LT(std::abs(along[plate.index(i, 19, 0) * 2]), 1.0) << i;
  const auto push = agent_stresses(plate, solved(plate, {{plate.index(0, 19, 0), test_support::kPlusX, 2.0}}).face_forces());
  const double e = 2 * (0.5 * kH) / 0.04 - 1;
  EXPECT_NEAR(push[plate.index(0, 19, 0) * 2], -2.0 / (kThick * 1.5 * kH) * (2 - 3 * e + e * e * e) / 4, 1.0);
}
