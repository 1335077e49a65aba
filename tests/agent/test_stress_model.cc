// What each rule type says of its stresses (agent::StressModel): the components it models, and
// whether its fields include a closed-form layer; and the agents alone (closed_forms = "left_out")
// differing from the full fields by those layers only.
#include <agent/coefficients.h>
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent/stress_components.h>
#include <workbench/symmetric_tensor.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "../support/agent_fixtures.h"

using namespace agent;
using namespace test_support;

namespace {

/// nx x ny agents of 5 mm, 2 mm thick, a rigid base if asked.
Grid plate_of(int nx, int ny, bool rigid_base) {
  Grid g = Grid::box(2, {nx, ny, 1}, Eigen::Vector3d(5e-3, 5e-3, 5e-3), 2e-3);
  if (rigid_base) g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  return g;
}

/// A uniform sigma_y on every agent of `g` (no packet shear, no row balance): the directional
/// stress components of that alone, with the closed forms as `closed`.
StressComponents uniform_push(const Grid& g, double sigma, ClosedForms closed) {
  std::vector<double> normal(2 * g.count(), 0.0), shear(g.count(), 0.0), balance(2 * balance_offset(g, 3), 0.0);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (!g.is_air(c)) normal[2 * c + 1] = sigma;
  DirectionalCoefficients k;
  k.closed_forms = closed;
  return directional_stress_components(g, normal, shear, balance, k, 0.3,
                                       {{g.index(g.cells[0] / 2, g.cells[1] - 1, 0), direction(1, false), 1.0}});
}

}  // namespace

TEST(StressModel, EachRuleTypeSaysWhatItModels) {
  const Grid g = plate_of(8, 8, true);
  const std::vector<EntryLoad> down{{g.index(4, 7, 0), direction(1, false), 1.0}};
  const std::vector<EntryLoad> along_x{{g.index(0, 4, 0), direction(0, true), 1.0}};
  const Coefficients k;
  const auto directional = stress_model(g, RuleSet::Directional, k, {}, down);
  for (int slot : {workbench::kXX, workbench::kYY, workbench::kXY}) EXPECT_TRUE(directional.models(slot)) << slot;
  EXPECT_FALSE(directional.models(workbench::kZZ));
  EXPECT_TRUE(directional.closed_forms);  // 2D, turning paths, closed forms added: the defaults
  // The columns' sigma along the load is 0 where no clamp holds them (here they cannot carry a
  // push onto the base at all); a load along x bends the plate clamped at its base: the clamp's
  // layer gives sigma_x too.
  const auto columns = stress_model(g, RuleSet::Columns, k, {}, down);
  EXPECT_TRUE(columns.models(workbench::kXX));
  EXPECT_FALSE(columns.models(workbench::kYY));
  EXPECT_TRUE(columns.models(workbench::kXY));
  EXPECT_FALSE(columns.closed_forms);
  const auto sideways = stress_model(g, RuleSet::Columns, k, {}, along_x);
  EXPECT_TRUE(sideways.models(workbench::kXX));
  EXPECT_TRUE(sideways.models(workbench::kYY));
  // The seed's rule sets give the normal stresses, no shear.
  for (RuleSet r : {RuleSet::Patent, RuleSet::Conserving}) {
    const auto seed = stress_model(g, r, k, {}, down);
    EXPECT_TRUE(seed.models(workbench::kXX) && seed.models(workbench::kYY));
    EXPECT_FALSE(seed.models(workbench::kXY));
  }
  // A combination models what either does.
  EXPECT_EQ((columns | directional).modelled, directional.modelled);
  EXPECT_TRUE((columns | directional).closed_forms);
  // No closed form: the agents alone, the mirror paths, 3D (its base layer is the local one).
  Coefficients alone = k, mirror = k;
  alone.directional.closed_forms = ClosedForms::LeftOut;
  mirror.directional.paths = Paths::Mirror;
  EXPECT_FALSE(stress_model(g, RuleSet::Directional, alone, {}, down).closed_forms);
  EXPECT_FALSE(stress_model(g, RuleSet::Directional, mirror, {}, down).closed_forms);
  const Grid block = Grid::box(3, {4, 4, 4}, Eigen::Vector3d(4e-3, 4e-3, 4e-3));
  const auto in_3d = stress_model(block, RuleSet::Directional, k, {}, {{block.index(2, 3, 2), direction(1, false), 1.0}});
  EXPECT_FALSE(in_3d.closed_forms);
  EXPECT_EQ(in_3d.modelled, 0b111111u);
  EXPECT_STREQ(find_coefficient("closed_forms")->choice_name(double(ClosedForms::LeftOut)), "left_out");
}

TEST(StressModel, TheAgentsAloneLackKirschsShearAndNothingElse) {
  // A 4 x 4-agent hole at the centre of a 40 x 40 plate without a rigid base (so no base layer),
  // under a uniform sigma_y of -1000 Pa: the full shear less the agents' alone is Kirsch's for the
  // circle of the hole's area (radius 4 h / sqrt(pi)) under the row's gross stress -1000 x 36 / 40.
  // At the agent (22, 22), 2.5 h from the hole's centre along both axes (45 degrees), that is
  // -s (a / r)^2 / 2 = 900 x (16 / pi) / (2 x 12.5) / 2 = 183.3465 Pa. sigma_y is the same to the bit.
  const int n = 40;
  Grid g = plate_of(n, n, false);
  for (int j = 18; j < 22; ++j)
    for (int i = 18; i < 22; ++i) g.make_air(g.index(i, j, 0));
  const auto full = uniform_push(g, -1000.0, ClosedForms::Added);
  const auto alone = uniform_push(g, -1000.0, ClosedForms::LeftOut);
  const std::size_t at = g.index(22, 22, 0);
  EXPECT_NEAR(full.shear[at] - alone.shear[at], 900.0 * 1.28 / std::acos(-1.0) / 2, 1e-9);
  EXPECT_NEAR(full.shear[at] - alone.shear[at], 183.3465, 1e-4);
  EXPECT_EQ(alone.shear[at], 0.0);  // a uniform sigma_y has no shear of its own
  const auto kirsch = hole_shear(g, 1, [&] {
    std::vector<double> normal(2 * g.count(), 0.0);
    for (std::size_t c = 0; c < g.count(); ++c)
      if (!g.is_air(c)) normal[2 * c + 1] = -1000.0;
    return normal;
  }());
  for (std::size_t c = 0; c < g.count(); ++c) {
    EXPECT_EQ(full.sigma[2 * c + 1], alone.sigma[2 * c + 1]);
    EXPECT_NEAR(full.shear[c] - alone.shear[c], kirsch[c], 1e-9) << c;
  }
}

TEST(StressModel, TheAgentsAloneLackTheBaseLayer) {
  // No hole, a rigid base: the full sigma_x less the agents' alone is the half-plane's layer, which
  // on the base row holds sigma_x near nu sigma_y = -300 Pa under the middle of a wide uniform
  // pressure (its modes at height h / 2 reach it to within a few percent), and fades upward.
  const int n = 40;
  const Grid g = plate_of(n, n, true);
  const auto full = uniform_push(g, -1000.0, ClosedForms::Added);
  const auto alone = uniform_push(g, -1000.0, ClosedForms::LeftOut);
  const auto layer = [&](int i, int j) {
    const std::size_t c = g.index(i, j, 0);
    return full.sigma[2 * c] - alone.sigma[2 * c];
  };
  EXPECT_NEAR(layer(n / 2, 0), -300.0, 15.0);  // -288.75
  EXPECT_LT(std::abs(layer(n / 2, n - 1)), 0.1 * std::abs(layer(n / 2, 0)));
  for (std::size_t c = 0; c < g.count(); ++c) {
    EXPECT_EQ(full.sigma[2 * c + 1], alone.sigma[2 * c + 1]);
    EXPECT_EQ(alone.sigma[2 * c], 0.0);  // a uniform sigma_y: no tie
    EXPECT_EQ(alone.shear[c], 0.0);
  }
  // In 3D the closed forms are not built: left out changes nothing.
  Grid block = Grid::box(3, {6, 6, 6}, Eigen::Vector3d(4e-3, 4e-3, 4e-3));
  block.set_boundary(block.box_side(kMinusY), Boundary::Rigid);
  Coefficients k, k_alone;
  k_alone.directional.closed_forms = ClosedForms::LeftOut;
  const std::vector<EntryLoad> loads{{block.index(2, 5, 3), direction(1, false), 1.0}};
  LoadTransfer m(block, kMaterial, k, RuleSet::Directional);
  m.solve(loads);
  const auto normal = agent_stresses(block, m.face_forces());
  const auto a = directional_stress_components(block, normal, m.shear_stress(), m.balance_slopes(), k.directional, 0.3, loads);
  const auto b = directional_stress_components(block, normal, m.shear_stress(), m.balance_slopes(), k_alone.directional, 0.3, loads);
  EXPECT_EQ(a.sigma, b.sigma);
  EXPECT_EQ(a.shear, b.shear);
}
