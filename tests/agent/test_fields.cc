// Stress, strain and displacement from face forces, against closed forms.
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent/state.h>
#include <agent/transfer.h>

#include <gtest/gtest.h>

#include <functional>

using namespace agent;

TEST(AgentFields, StressIsMeanFaceForceOverAreaCompressionNegative) {
  Grid g = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(0.5, 0.25, 1), 0.1);
  // faces -x, +x, -y, +y
  const std::vector<double> f{1.0, 3.0, 2.0, 4.0};
  const auto s = agent_stresses(g, f);
  EXPECT_DOUBLE_EQ(s[0], -2.0 / (0.25 * 0.1));  // x faces have area h_y * t
  EXPECT_DOUBLE_EQ(s[1], -3.0 / (0.5 * 0.1));   // y faces have area h_x * t
}

TEST(AgentFields, PlaneStressHooke) {
  Grid g = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(1, 1, 1));
  const Material m{200.0, 0.25};
  const auto e = agent_strains(g, m, {-10.0, -20.0});
  EXPECT_DOUBLE_EQ(e[0], (-10.0 + 0.25 * 20.0) / 200.0);
  EXPECT_DOUBLE_EQ(e[1], (-20.0 + 0.25 * 10.0) / 200.0);
  EXPECT_DOUBLE_EQ(e[2], 0.25 * 30.0 / 200.0);
}

TEST(AgentFields, UniformStrainIntegratesToLinearDisplacementFromTheDatum) {
  for (int dim : {2, 3}) {
    Grid g = Grid::box(dim, {6, 5, 4}, Eigen::Vector3d(0.5, 0.25, 2.0));
    g.set_boundary(g.box_side(2), Boundary::Rigid);  // base: u_y = 0 at y = 0
    std::vector<double> eps(g.count() * 3);
    for (std::size_t c = 0; c < g.count(); ++c) {
      eps[3 * c] = 1e-3;
      eps[3 * c + 1] = -2e-3;
      eps[3 * c + 2] = 3e-3;
    }
    // x: no rigid side, datum at the load; z likewise.
    const std::vector<EntryLoad> loads{{g.index(2, 4, dim == 3 ? 1 : 0), direction(1, false), 1.0}};
    const auto datums = choose_datums(g, loads);
    EXPECT_DOUBLE_EQ(datums[1], 0.0);  // the rigid base
    EXPECT_DOUBLE_EQ(datums[0], 2.5);  // the centre of the loaded agent
    if (dim == 3) {
      EXPECT_DOUBLE_EQ(datums[2], 1.5);
    }
    const auto u = node_displacements(g, eps, datums);
    const auto nn = g.node_counts();
    for (int k = 0; k < nn[2]; ++k)
      for (int j = 0; j < nn[1]; ++j)
        for (int i = 0; i < nn[0]; ++i) {
          const std::size_t n = g.node_index(i, j, k);
          EXPECT_NEAR(u[n * dim + 0], 1e-3 * (i - 2.5) * 0.5, 1e-15);
          EXPECT_NEAR(u[n * dim + 1], -2e-3 * j * 0.25, 1e-15);
          if (dim == 3) {
            EXPECT_NEAR(u[n * dim + 2], 3e-3 * (k - 1.5) * 2.0, 1e-15);
          }
        }
  }
}

namespace {

/// The march (node_displacements_marched) on a block of 6 x 5 (x 4) agents of 0.5 x 0.25 (x 2) m with
/// its rigid base at y = 0, loaded down at agent (1, 4, 1): each agent's strain is strain(its
/// centre), its shear tau_xy (and tau_yz in 3D) the given constants; every node's displacement
/// must be expected(the node).
void check_march(int dim, const Material& m, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& strain,
                 double tau_xy, double tau_yz,
                 const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& expected) {
  const std::array<int, 3> n{6, 5, 4};
  const Eigen::Vector3d h(0.5, 0.25, 2.0);
  Grid g = Grid::box(dim, n, h);
  g.set_boundary(g.box_side(2), Boundary::Rigid);
  const int shears = dim == 3 ? 3 : 1;
  std::vector<double> eps(g.count() * 3), shear(g.count() * shears, 0.0);
  for (int k = 0; k < (dim == 3 ? n[2] : 1); ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        const std::size_t c = g.index(i, j, k);
        const Eigen::Vector3d e = strain(Eigen::Vector3d(i + 0.5, j + 0.5, dim == 3 ? k + 0.5 : 0.0).cwiseProduct(h));
        for (int a = 0; a < 3; ++a) eps[3 * c + a] = e[a];
        shear[c * shears + shear_pair(0, 1)] = tau_xy;
        if (dim == 3) shear[c * shears + shear_pair(1, 2)] = tau_yz;
      }
  const std::vector<EntryLoad> loads{{g.index(1, 4, dim == 3 ? 1 : 0), direction(1, false), 1.0}};
  const auto u = node_displacements_marched(g, eps, shear, m, choose_datums(g, loads), 1);
  const auto nn = g.node_counts();
  for (int k = 0; k < nn[2]; ++k)
    for (int j = 0; j < nn[1]; ++j)
      for (int i = 0; i < nn[0]; ++i) {
        const std::size_t node = g.node_index(i, j, k);
        const Eigen::Vector3d want = expected(Eigen::Vector3d(i, j, k).cwiseProduct(h));
        for (int a = 0; a < dim; ++a)
          EXPECT_NEAR(u[node * dim + a], want[a], 1e-15) << dim << "D, u_" << "xyz"[a] << " at node " << i << j << k;
      }
}

}  // namespace

TEST(AgentFields, TheMarchAcrossGivesLinearFieldsTheirClosedForms) {
  // A uniform strain and a uniform shear strain gamma (tau = G gamma in the pairs with y) give
  //   u_y = eps_y y (up the columns from the base),
  //   u_l = eps_l (x_l - the line's centre) + gamma y  (l = x, and z in 3D: the line's constant the
  //         mean of the columns' marches du_l/dy = gamma - du_y/dx_l = gamma),
  // whatever the load's position: the march reads no datum across. The lines' centres: x = 1.5 m,
  // z = 4 m; tau_yz = -G gamma / 2. In 2D eps_x = 0: the base holds u_x = 0, so a uniform eps_x is
  // not a field the plate can take, and 2D's u_x is the field closest to both increments (the next
  // test); every field the base allows comes out as it is.
  const Material m{200e9, 0.25};
  const double G = m.young / (2 * (1 + m.poisson)), gamma = 4e-4;
  for (int dim : {2, 3}) {
    const double eps_x = dim == 3 ? 1e-3 : 0.0;
    check_march(
        dim, m, [&](const Eigen::Vector3d&) { return Eigen::Vector3d(eps_x, -2e-3, 3e-3); }, G * gamma, -0.5 * G * gamma,
        [&](const Eigen::Vector3d& p) {
          return Eigen::Vector3d(eps_x * (p.x() - 1.5) + gamma * p.y(), -2e-3 * p.y(), 3e-3 * (p.z() - 4) - 0.5 * gamma * p.y());
        });
  }
}

TEST(AgentFields, TheLateralDisplacementIn2DIsTheFieldClosestToBothIncrements) {
  // Two agents of 0.5 x 0.25 m side by side on a rigid base, eps_x = e uniform, no other strain:
  // the row says the ends move apart by e h_x each, the columns (held at the base, gamma = 0,
  // u_y = 0) say they do not move. With the top nodes u_0, u_1, u_2 the grid's least squares is
  //   (u_1 - u_0 - e h_x)^2 / 2 + (u_2 - u_1 - e h_x)^2 / 2 + rho (u_0^2 / 2 + u_1^2 + u_2^2 / 2)
  // (the free top's and the sides' edges weigh half), rho = r (h_x / h_y)^2 = 4 r, r = (1 + nu^2)
  // / (4 (1 + nu)^2); by symmetry u_1 = 0 and u_2 = -u_0 = e h_x / (1 + rho). The march before it
  // (the row's line, its constant the columns' mean) gave e h_x.
  const Material m{200e9, 0.25};
  Grid g = Grid::box(2, {2, 1, 1}, Eigen::Vector3d(0.5, 0.25, 1));
  g.set_boundary(g.box_side(2), Boundary::Rigid);
  const double e = 1e-3, r = (1 + 0.25 * 0.25) / (4 * 1.25 * 1.25);  // r = 0.17
  const std::vector<double> eps{e, 0, 0, e, 0, 0}, shear{0, 0};
  const std::vector<EntryLoad> loads{{g.index(0, 0, 0), direction(1, false), 1.0}};
  const auto u = node_displacements_marched(g, eps, shear, m, choose_datums(g, loads), 1);
  const double side = 0.5 * e / (1 + 4 * r);  // 2.97619e-4 m
  EXPECT_NEAR(side, 2.97619e-4, 1e-9);
  EXPECT_NEAR(u[g.node_index(0, 1, 0) * 2], -side, 1e-17);
  EXPECT_NEAR(u[g.node_index(1, 1, 0) * 2], 0.0, 1e-17);
  EXPECT_NEAR(u[g.node_index(2, 1, 0) * 2], side, 1e-17);
  for (int i = 0; i <= 2; ++i) {
    EXPECT_EQ(u[g.node_index(i, 0, 0) * 2], 0.0);  // the base holds it
    EXPECT_EQ(u[g.node_index(i, 1, 0) * 2 + 1], 0.0);  // no eps_y, no u_y
  }
}

TEST(AgentFields, TheMarchGivesABendingFieldItsClosedFormOnTheSidesToo) {
  // eps_y = c x + d z (d = 0 in 2D), no other strain: a compatible field (every second derivative
  // of a linear strain is 0), the plane sections of a column bent about the base. Its closed form
  // with the base at y = 0 held: u_y = (c x + d z) y, u_x = -c y^2 / 2, u_z = -d y^2 / 2. The side
  // nodes' u_y is the columns' lines extrapolated to the side; taking the side column's own line
  // (its value half an agent inside) would be off there by c h_x / 2 y, halve du_y/dx in the side
  // columns, and leave u_x off by a rotation on every line across.
  const Material m{200e9, 0.25};
  const double c = 3e-3;
  for (int dim : {2, 3}) {
    const double d = dim == 3 ? -2e-3 : 0.0;
    check_march(
        dim, m, [&](const Eigen::Vector3d& p) { return Eigen::Vector3d(0, c * p.x() + d * p.z(), 0); }, 0, 0,
        [&](const Eigen::Vector3d& p) {
          return Eigen::Vector3d(-c * p.y() * p.y() / 2, (c * p.x() + d * p.z()) * p.y(), -d * p.y() * p.y() / 2);
        });
  }
}

TEST(VonMises, ClosedFormsInBothOrders) {
  using workbench::von_mises;
  using workbench::VonMisesForm;
  const workbench::SymmetricTensor uniaxial{-100, 0, 0, 0, 0, 0}, shear{0, 0, 0, 2, 0, 0}, equal{5, 5, 0, 0, 0, 0};
  for (auto form : {VonMisesForm::General, VonMisesForm::PlaneStress}) {
    EXPECT_DOUBLE_EQ(von_mises(uniaxial, form), 100);
    EXPECT_DOUBLE_EQ(von_mises(shear, form), 2 * std::sqrt(3.0));
    EXPECT_DOUBLE_EQ(von_mises(equal, form), 5);  // equal biaxial: the uniaxial value
  }
  // 3D: hydrostatic pressure has none; each shear counts sqrt(3).
  EXPECT_EQ(von_mises(workbench::SymmetricTensor{-7, -7, -7, 0, 0, 0}), 0.0);
  EXPECT_DOUBLE_EQ(von_mises(workbench::SymmetricTensor{0, 0, 0, 1, 1, 1}), 3.0);
  // The agents: plane stress in 2D, the general form in 3D.
  const workbench::SymmetricTensor s{3, -1, 0, 2, 0, 0};
  EXPECT_EQ(agent_von_mises(s, 2), von_mises(s, VonMisesForm::PlaneStress));
  EXPECT_EQ(agent_von_mises(s, 3), von_mises(s));
  EXPECT_NEAR(agent_von_mises(s, 2), std::sqrt(9.0 + 3 + 1 + 12), 1e-14);
}

TEST(Diagnostics, PlusEqualsAddsEveryTally) {
  Diagnostics a, b;
  a.agents_generated = 1, a.agent_updates = 2, a.packet_moves = 3, a.applied = 4, a.rigid_reaction = 5;
  a.passed_out = 6, a.dropped = 7, a.lost = 8, a.lateral_reaction = 9, a.lateral_passed_out = 10;
  a.lateral_dropped = 11, a.returned_rigid = 12, a.returned_free = 13, a.unfinished = 14;
  b = a;
  b += a;
  EXPECT_EQ(b.agents_generated, 2u);
  EXPECT_EQ(b.agent_updates, 4u);
  EXPECT_EQ(b.packet_moves, 6u);
  const double Diagnostics::*tallies[] = {&Diagnostics::applied, &Diagnostics::rigid_reaction, &Diagnostics::passed_out,
                                          &Diagnostics::dropped, &Diagnostics::lost, &Diagnostics::lateral_reaction,
                                          &Diagnostics::lateral_passed_out, &Diagnostics::lateral_dropped,
                                          &Diagnostics::returned_rigid, &Diagnostics::returned_free,
                                          &Diagnostics::unfinished};
  for (auto t : tallies) EXPECT_EQ(b.*t, 2 * (a.*t));
}

// The one call: the record holds agent_stresses' normal stresses and agent_strains' strains; a
// pull is the push negated (every field, to the bit); the field table reads the record.
TEST(AgentState, SolveStateHoldsTheFieldsOfTheFaceForces) {
  Grid g = Grid::box(2, {4, 5, 1}, Eigen::Vector3d(0.01, 0.01, 1), 0.002);
  g.set_boundary(g.box_side(direction(1, false)), Boundary::Rigid);
  const Material steel{206e9, 0.3};
  Coefficients k;
  LoadTransfer model(g, steel, k, RuleSet::Conserving);
  const std::size_t entry = g.index(1, 4, 0);
  const auto push = solve_state(model, {{entry, direction(1, false), 2.0}}, {}, 0.5);
  const auto normal = agent_stresses(g, model.face_forces());
  const auto strain = agent_strains(g, steel, normal);
  ASSERT_EQ(push.stress.size(), g.count());
  EXPECT_NEAR(push.diagnostics.applied, 1.0, 1e-15);  // the factor scales the load
  for (std::size_t c = 0; c < g.count(); ++c) {
    EXPECT_EQ(push.stress[c][workbench::kXX], normal[2 * c] + 0.0);
    EXPECT_EQ(push.stress[c][workbench::kYY], normal[2 * c + 1] + 0.0);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(push.strain[c][a], strain[3 * c + a] + 0.0);
    const auto& vm = state_field("von_mises");
    EXPECT_EQ(vm.read(push, c, 0, 2), agent_von_mises(push.stress[c], 2));
  }
  EXPECT_LT(push.stress[entry][workbench::kYY], 0);  // compression under the push
  const auto pull = solve_state(model, {{entry, direction(1, false), -2.0}}, {}, 0.5);
  for (std::size_t c = 0; c < g.count(); ++c)
    for (int v = 0; v < workbench::kVoigtCount; ++v) ASSERT_EQ(pull.stress[c][v], -push.stress[c][v] + 0.0);
  for (std::size_t n = 0; n < push.displacement.size(); ++n) ASSERT_EQ(pull.displacement[n], -push.displacement[n] + 0.0);
}

TEST(FieldTable, RowsAreConsistent) {
  for (const auto& f : kStateFields) {
    SCOPED_TRACE(f.name);
    EXPECT_LE(f.components(2), f.components(3));
    EXPECT_GT(f.components(2), 0);
    if (f.slot >= 0) {
      EXPECT_LE(f.slot + f.components(3), workbench::kVoigtCount + 1);  // compare::kStressSlots
    }
    for (int k = 0; k < f.components(3); ++k) {
      if (f.vtu != VtuLayout::Scalars) {
        EXPECT_FALSE(vtu_label(f.columns[k]).empty()) << f.columns[k];
      }
    }
  }
}
