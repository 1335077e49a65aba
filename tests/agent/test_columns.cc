// The column rule set (agent/columns.h): closed forms of a cantilever and a simply supported beam
// (Euler-Bernoulli with Timoshenko's shear), Navier's and Jourawski's distributions, the statics'
// reactions, odd in the load and linear, a notch's column, the bonded supports' thrust, and what
// it refuses before a run.
#include <agent/columns.h>
#include <agent/load_transfer.h>
#include <agent_study.h>
#include <carry_check.h>

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>

#include "../support/agent_fixtures.h"
#include "../support/column_refusal.h"
#include "../support/study_error.h"

using namespace agent;
using test_support::column_refusal;
using test_support::kMinusX, test_support::kPlusX, test_support::kMinusY, test_support::kPlusY;

namespace {

const Material kSteel{206e9, 0.3};
constexpr double kH = 5e-3, kThick = 2e-3;
const double kG = kSteel.young / (2 * (1 + kSteel.poisson));

/// nx x ny agents of 5 mm, 2 mm thick.
Grid beam(int nx, int ny) { return Grid::box(2, {nx, ny, 1}, Eigen::Vector3d(kH, kH, kH), kThick); }

/// Clamped at x = 0 (its -x side rigid).
Grid cantilever(int nx, int ny) {
  Grid g = beam(nx, ny);
  g.set_boundary(g.box_side(kMinusX), Boundary::Rigid);
  return g;
}

/// On two supports: the bottom faces of the first and the last `width` columns rigid.
Grid supported(int nx, int ny, int width = 1) {
  Grid g = beam(nx, ny);
  std::vector<BoundaryFace> faces;
  for (int i = 0; i < width; ++i) faces.push_back({g.index(i, 0, 0), kMinusY}), faces.push_back({g.index(nx - 1 - i, 0, 0), kMinusY});
  g.set_boundary(faces, Boundary::Rigid);
  return g;
}

/// `force` N down (-y) on the top face of column i.
EntryLoad down(const Grid& g, int i, double force) { return {g.index(i, g.cells[1] - 1, 0), kMinusY, force}; }

LoadTransfer solved(const Grid& g, const std::vector<EntryLoad>& loads) {
  LoadTransfer m(g, kSteel, Coefficients{}, RuleSet::Columns);
  m.solve(loads);
  return m;
}

double sigma_x(const LoadTransfer& m, std::size_t cell) { return agent_stresses(m.grid(), m.face_forces())[cell * 2]; }
double u_y(const LoadTransfer& m, int i, int j) { return m.displacement()[m.grid().node_index(i, j, 0) * 2 + 1]; }

}  // namespace

// A cantilever 200 x 40 mm clamped at x = 0, 2 N down on the top of its last column (x_l = 197.5
// mm): the deflection of the centroid line at x = 195 mm is Euler-Bernoulli's P x^2 (3 x_l - x) /
// (6 E I) plus Timoshenko's shear P x / (k G A), k = 5/6 (the energy of Jourawski's parabola).
TEST(Columns, CantileverDeflectionIsBeamTheorys) {
  const Grid g = cantilever(40, 8);
  const double P = 2, xl = 0.1975, x = 0.195, I = kThick * std::pow(0.04, 3) / 12, A = 0.04 * kThick;
  const auto m = solved(g, {down(g, 39, P)});
  const double expected = -(P * x * x * (3 * xl - x) / (6 * kSteel.young * I) + P * x / (5.0 / 6 * kG * A));
  EXPECT_NEAR(u_y(m, 39, 4) / expected, 1.0, 2e-3);  // node row 4: the centroid (y = 20 mm)
  // The clamp holds: no rotation, no axial displacement, no deflection of the centroid on its plane
  // (the Poisson strain moves its other nodes across, which a study's rigid face then holds).
  for (int j = 0; j <= 8; ++j) EXPECT_EQ(m.displacement()[g.node_index(0, j, 0) * 2 + 0], 0.0);
  EXPECT_EQ(u_y(m, 0, 4), 0.0);
  // Every node of the body moved down, more with the distance from the clamp.
  for (int i = 1; i <= 40; ++i) EXPECT_LT(u_y(m, i, 4), u_y(m, i - 1, 4));
}

// Navier: sigma_x = M (y - y_c) / I over each column, M = P (x_l - x) (top in tension under a
// downward tip load); Jourawski: tau_xy = -(3 V / 2 A) (1 - 4 z^2 / H^2) averaged over each agent,
// negative under a downward load, largest 1.5 V / A at the centroid, integrating to V.
TEST(Columns, NavierAndJourawskiOverAColumn) {
  const Grid g = cantilever(40, 8);
  const double P = 2, xl = 0.1975, I = kThick * std::pow(0.04, 3) / 12, A = 0.04 * kThick;
  const auto m = solved(g, {down(g, 39, P)});
  for (int i : {0, 10, 25}) {
    const double x = (i + 0.5) * kH, M = P * (xl - x);
    double shear = 0;
    for (int j = 0; j < 8; ++j) {
      const std::size_t c = g.index(i, j, 0);
      const double y = (j + 0.5) * kH - 0.02;
      EXPECT_NEAR(sigma_x(m, c), M * y / I, 1e-9 * M * 0.02 / I) << i << ", " << j;
      // The parabola's mean over the agent: 1 - 4 (z^2 + h^2 / 12) / H^2.
      const double mean = 1.5 * P / A * (1 - 4 * (y * y + kH * kH / 12) / (0.04 * 0.04));
      EXPECT_NEAR(m.shear_stress()[c], -mean, 1e-9 * P / A) << i << ", " << j;
      shear += m.shear_stress()[c] * kH * kThick;
    }
    EXPECT_NEAR(shear, -P, 1e-12);  // the clamp's column too: the clamp takes the whole load
    EXPECT_NEAR(std::abs(m.shear_stress()[g.index(i, 3, 0)]), 1.5 * P / A * (1 - 4 * (kH * kH / 4 + kH * kH / 12) / (0.04 * 0.04)), 1e-6);
  }
  // sigma_y is the clamp's layer alone (test_columns_root.cc): none left 125 mm from the clamp.
  for (int j = 0; j < 8; ++j)
    EXPECT_LT(std::abs(agent_stresses(g, m.face_forces())[g.index(25, j, 0) * 2 + 1]), 1e-9 * std::abs(sigma_x(m, g.index(25, 0, 0))));
}

// The reactions are the load's: the clamp takes V = P and M = P x_l; two supports share it by the
// balance of moments. The load balance says so.
TEST(Columns, ReactionsEqualTheLoad) {
  const Grid g = cantilever(40, 8);
  const auto c = column_statics(g, {down(g, 39, 2.0)});
  EXPECT_EQ(c.plan.holding, Holding::Clamp);
  EXPECT_DOUBLE_EQ(c.reactions[0], 2.0);
  EXPECT_NEAR(c.clamp_moment, 2.0 * 0.1975, 1e-15);
  const auto m = solved(g, {down(g, 39, 2.0)});
  EXPECT_EQ(m.diagnostics().applied, 2.0);
  EXPECT_EQ(m.diagnostics().rigid_reaction, 2.0);
  EXPECT_EQ(m.diagnostics().passed_out + m.diagnostics().dropped + m.diagnostics().lost, 0.0);
  EXPECT_EQ(m.diagnostics().agents_generated, 320u);
  // Supports at x = 2.5 and 197.5 mm, 3 N at x = 52.5 mm: 3 x 145 / 195 and 3 x 50 / 195 N.
  const Grid s = supported(40, 8);
  const auto b = column_statics(s, {down(s, 10, 3.0)});
  EXPECT_EQ(b.plan.holding, Holding::Supports);
  EXPECT_NEAR(b.reactions[0], 3.0 * 145 / 195, 1e-14);
  EXPECT_NEAR(b.reactions[1], 3.0 * 50 / 195, 1e-14);
}

// A load pushing up (+y) from the underside gives the downward load's fields negated, to the bit:
// sigma_x, the shear, the displacement; sigma_y, where the load enters, is its loads' layer
// (test_columns_root.cc). Two loads give the sum of each one's fields.
TEST(Columns, OddInTheLoadAndLinear) {
  for (const Grid& g : {cantilever(30, 6), supported(31, 6, 2)}) {
    const auto push = solved(g, {down(g, 20, 2.0)});
    const auto pull = solved(g, {{g.index(20, 0, 0), kPlusY, 2.0}});
    for (std::size_t i = 0; i < push.face_forces().size(); ++i)
      if (i % 4 < 2) {  // the faces across x
        ASSERT_EQ(push.face_forces()[i], -pull.face_forces()[i] + 0.0) << i;
      }
    for (auto [x, y] : {std::pair{&push.shear_stress(), &pull.shear_stress()}, std::pair{&push.displacement(), &pull.displacement()}})
      for (std::size_t i = 0; i < x->size(); ++i) ASSERT_EQ((*x)[i], -(*y)[i] + 0.0) << i;
    const auto a = solved(g, {down(g, 12, 1.0)}), b = solved(g, {down(g, 25, 3.0)});
    const auto both = solved(g, {down(g, 12, 1.0), down(g, 25, 3.0)});
    double scale = 0;
    for (double v : both.displacement()) scale = std::max(scale, std::abs(v));
    for (std::size_t i = 0; i < both.displacement().size(); ++i)
      ASSERT_NEAR(both.displacement()[i], a.displacement()[i] + b.displacement()[i], 1e-12 * scale) << i;
    for (std::size_t i = 0; i < both.shear_stress().size(); ++i)
      ASSERT_NEAR(both.shear_stress()[i], a.shear_stress()[i] + b.shear_stress()[i], 1e-9) << i;
  }
}

// A notch (the two bottom agents of column 20 air): that column's centroid rises by one agent,
// its area and second moment are those of its six agents, and its sigma_x is Navier's about them.
// Toward the clamp the section regains the notch's depth at 45 degrees (column 19: rows 1-7).
TEST(Columns, NotchShiftsItsColumnsCentroid) {
  Grid g = cantilever(40, 8);
  g.make_air(g.index(20, 0, 0)), g.make_air(g.index(20, 1, 0));
  const auto c = column_statics(g, {down(g, 39, 2.0)});
  EXPECT_NEAR(c.centroid[21], 0.020, 1e-15);
  EXPECT_NEAR(c.centroid[19], 0.0225, 1e-15);
  EXPECT_NEAR(c.centroid[18], 0.020, 1e-15);
  EXPECT_NEAR(c.centroid[20], 0.025, 1e-15);
  EXPECT_NEAR(c.area[20], 0.030 * kThick, 1e-18);
  EXPECT_NEAR(c.inertia[20], kThick * std::pow(0.030, 3) / 12, 1e-20);
  const auto m = solved(g, {down(g, 39, 2.0)});
  const double M = 2.0 * (0.1975 - 0.1025);
  EXPECT_NEAR(sigma_x(m, g.index(20, 7, 0)), M * (0.0375 - 0.025) / c.inertia[20], 1e-6);
}

// Supports free to slide (no thrust): a beam on supports L = 200 mm apart, 2 N at midspan, deflects
// by P x (3 L^2 - 4 x^2) / (48 E I) + P x / (2 k G A) at x from a support (P L^3 / (48 E I) + P L /
// (4 k G A) at midspan). Bonded (the agents' rigid faces), the
// supports hold the bottom fibre: its ends do not move apart, the span is compressed by the
// thrust, and the beam deflects less.
TEST(Columns, SimplySupportedBeamAndTheBondedThrust) {
  const Grid g = supported(41, 8);  // supports' centres x = 2.5 and 202.5 mm, the load at 102.5 mm
  const double P = 2, L = 0.2, I = kThick * std::pow(0.04, 3) / 12, A = 0.04 * kThick;
  const std::vector<EntryLoad> loads{down(g, 20, P)};
  auto c = column_statics(g, loads);
  TransferResults free;
  free.faces.assign(g.count() * 4, 0), free.generation.assign(g.count(), -1), free.shear.assign(g.count(), 0);
  column_fields(g, kSteel, c, loads, free);
  auto mid = [&](const std::vector<double>& u) {  // at the supports' level, 2.5 mm either side of midspan
    return 0.5 * (u[g.node_index(20, 0, 0) * 2 + 1] + u[g.node_index(21, 0, 0) * 2 + 1]);
  };
  const double x = 0.0975;
  const double expected = -(P * x * (3 * L * L - 4 * x * x) / (48 * kSteel.young * I) + P * x / (2 * 5.0 / 6 * kG * A));
  EXPECT_NEAR(mid(free.displacement) / expected, 1.0, 2e-3);
  EXPECT_EQ(c.thrust, 0.0);
  add_bonded_thrust(c);
  EXPECT_GT(c.thrust, 0.0);
  EXPECT_EQ(c.n[20], -c.thrust);
  EXPECT_EQ(c.n[0], 0.0);
  const auto bonded = solved(g, loads);
  const auto& u = bonded.displacement();
  const double ux1 = u[g.node_index(1, 0, 0) * 2], ux2 = u[g.node_index(40, 0, 0) * 2];
  EXPECT_NEAR(ux2 - ux1, 0.0, 1e-9 * std::abs(expected));  // the bottom fibre between the supports
  EXPECT_GT(mid(u), mid(free.displacement));
}

// What the columns cannot carry is said in one sentence, before a run.
TEST(Columns, RefusesWhatItCannotCarry) {
  const Grid g = cantilever(10, 4);
  EXPECT_EQ(column_refusal(g, {down(g, 9, 1.0)}), "carried");
  EXPECT_NE(column_refusal(g, {down(g, 9, 1.0), {g.index(9, 2, 0), kMinusX, 1.0}}).find("loads along both x and y"), std::string::npos);
  // A load along the beam axis (the clamp's normal): the clamp lies ahead of it, the march carries it.
  EXPECT_NE(column_refusal(g, {{g.index(9, 2, 0), kMinusX, 1.0}}).find("form one support"), std::string::npos);
  Grid both = cantilever(10, 4);
  both.set_boundary(both.box_side(kPlusX), Boundary::Rigid);
  EXPECT_NE(column_refusal(both, {down(both, 5, 1.0)}).find("more than one plane"), std::string::npos);
  EXPECT_NE(column_refusal(beam(10, 4), {down(g, 5, 1.0)}).find("no rigid face"), std::string::npos);
  Grid plate = beam(10, 4);
  plate.set_boundary(plate.box_side(kMinusY), Boundary::Rigid);
  EXPECT_NE(column_refusal(plate, {down(plate, 5, 1.0)}).find("form one support"), std::string::npos);
  Grid three = supported(11, 4);
  three.set_boundary({{three.index(5, 0, 0), kMinusY}}, Boundary::Rigid);
  EXPECT_NE(column_refusal(three, {down(three, 3, 1.0)}).find("3 supports"), std::string::npos);
  Grid split = cantilever(10, 4);
  for (int j = 0; j < 4; ++j) split.make_air(split.index(5, j, 0));
  EXPECT_NE(column_refusal(split, {down(split, 9, 1.0)}).find("no agent between x = 25 mm and 30 mm"), std::string::npos);
}

// A case with rule_set = "columns" that the columns cannot carry (the seed plate on its base) is
// refused while it is read, naming agent.rule_set and the reason; the carry check of a cantilever
// case says how the columns carry it, and the directional rule set's refusal points to them.
TEST(Columns, StudyRefusesBeforeTheRunAndTheCarryCheckKnowsTheColumns) {
  const std::string plate = "[mesh]\nfile = \"" WORKBENCH_SOURCE_DIR "/meshes/plate2d.geo\"\n[mesh.parameters]\nh = 0.01\nlw = 0.02\n"
                            "[material]\nyoung = 206e9\npoisson = 0.3\nthickness = 0.002\n[boundary]\nrigid = [\"base\"]\n"
                            "[[load]]\ngroup = \"load\"\ndirection = \"-y\"\nforce = 2.0\n[agent]\nrule_set = \"columns\"\n";
  const auto error = test_support::study_error(plate);
  EXPECT_NE(error.find("agent.rule_set"), std::string::npos) << error;
  EXPECT_NE(error.find("the columns rule set cannot carry the loads: the rigid faces along the beam axis x form one support"),
            std::string::npos) << error;
  auto with = [](const std::string& rules) {
    std::string text;
    {
      std::ifstream in(WORKBENCH_SOURCE_DIR "/cases/cantilever.toml");
      text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto at = text.find("rule_set = \"");
    text.replace(at, text.find('\n', at) - at, "rule_set = \"" + rules + "\"");
    const auto mesh = text.find("../meshes/");
    text.replace(mesh, 10, WORKBENCH_SOURCE_DIR "/meshes/");
    workbench::CaseFile file(test_support::write_file("cantilever.toml", text));
    return agent_study::load_agent_study(file);
  };
  const auto columns = with("columns");
  const auto carried = agent_study::carry_check(columns);
  ASSERT_EQ(carried.size(), 1u);
  EXPECT_FALSE(carried[0].refused());
  EXPECT_EQ(carried[0].march, kMinusX);
  EXPECT_NEAR(carried[0].exits.rigid, 0.04 * 0.002, 1e-15);
  EXPECT_NE(carried[0].describe(columns).find("carries by bending: columns along x to the clamp at x = 0 mm"), std::string::npos)
      << carried[0].describe(columns);
  const auto directional = with("directional");
  const auto refused = agent_study::carry_check(directional);
  ASSERT_EQ(refused.size(), 1u);
  EXPECT_TRUE(refused[0].refused());
  EXPECT_NE(refused[0].describe(directional).find("rule_set = \"columns\" carries it"), std::string::npos)
      << refused[0].describe(directional);
}

// The same beam on tiles (agent::tile): every stress and displacement the dense grid's, slot by slot
// and node by node (the columns are gathered by coordinates, not by id order).
TEST(Columns, TiledGridGivesTheDenseFields) {
  Grid dense = supported(70, 20, 3);
  dense.make_air(dense.index(35, 0, 0)), dense.make_air(dense.index(35, 1, 0));  // a notch
  const Grid tiled = tile(dense);
  ASSERT_TRUE(tiled.tiled());
  const auto a = solved(dense, {down(dense, 30, 2.0)}), b = solved(tiled, {down(tiled, 30, 2.0)});
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 70; ++i) {
      const std::size_t c = dense.index(i, j, 0), d = tiled.index(i, j, 0);
      ASSERT_EQ(a.shear_stress()[c], b.shear_stress()[d]) << i << ", " << j;
      ASSERT_EQ(a.face_forces()[c * 4], b.face_forces()[d * 4]) << i << ", " << j;
    }
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 70; ++i)
      for (int k = 0; k < 2; ++k)
        ASSERT_EQ(a.displacement()[dense.node_index(i, j, 0) * 2 + k], b.displacement()[tiled.node_index(i, j, 0) * 2 + k]);
}
