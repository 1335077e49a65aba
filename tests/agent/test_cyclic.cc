// Readings 2 and 6 of the patent rule set (the cyclic transfer): hand-computed face forces on tiny
// grids, the load balance, termination and its refusals, symmetry, and the sweep's rules in
// work-list form reproducing the sweep.
#include <agent/cyclic_transfer.h>
#include <agent/load_transfer.h>

#include <gtest/gtest.h>

#include <random>

#include "../support/agent_fixtures.h"

using namespace agent;
using namespace test_support;  // plate, face, coefficients, kMaterial, the face directions

namespace {

Readings with(bool every, bool returns) {
  Readings r;
  r.every_agent_all_operations = every;
  r.boundaries_return = returns;
  return r;
}

double balance_gap(const Diagnostics& d) { return d.applied - (d.rigid_reaction + d.passed_out + d.dropped + d.lost); }

}  // namespace

TEST(AgentCyclic, FrictionGoesBackUnderReading2) {
  // Two agents side by side on a rigid base, 1 N down on the left one; alpha1 = alpha2 = 0.5,
  // alpha3 = 0.4, beta = 1 (no push), gamma = 0.05. Wave by wave (F = a friction load):
  //   entry at 0 (1):  TOP0 += 0.5; down 0.25 -> base (reaction); friction 0.4 out at the
  //                    left side (passed out) and 0.4 to agent 1.
  //   F at 1 (0.4):    TOP1 += 0.2; down 0.1 -> base; friction 0.16 out at the right side and
  //                    0.16 BACK to agent 0 (reading 2).
  //   F at 0 (0.16):   TOP0 += 0.08; down 0.04 <= gamma dropped; friction 0.064 out at the
  //                    left and 0.064 to agent 1.
  //   F at 1 (0.064):  TOP1 += 0.032; down 0.016 dropped; friction 0.0256 <= gamma dropped twice.
  const Grid g = plate(2, 1);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.4, 1.0, 0.05), RuleSet::Patent, with(true, false));
  m.solve({{g.index(0, 0, 0), kMinusY, 1.0}});
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusY), 0.5 + 0.08);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kMinusY), 0.25);
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kPlusY), 0.2 + 0.032);
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kMinusY), 0.1);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusX), 0.0);  // friction loads the TOP, not the side faces
  const auto& d = m.diagnostics();
  EXPECT_DOUBLE_EQ(d.rigid_reaction, 0.35);
  EXPECT_DOUBLE_EQ(d.passed_out, 0.4 + 0.16 + 0.064);
  EXPECT_DOUBLE_EQ(d.dropped, 0.04 + 0.016 + 2 * 0.0256);
  // Lost per agent visit: input less what it passes on (negative: the coefficients create load).
  EXPECT_NEAR(d.lost, (1 - 0.25 - 0.8) + (0.4 - 0.1 - 0.32) + (0.16 - 0.04 - 0.128) + (0.064 - 0.016 - 0.0512),
              1e-15);
  EXPECT_NEAR(balance_gap(d), 0.0, 1e-15);
  EXPECT_EQ(d.agent_updates, 4u);
  EXPECT_EQ(m.generation()[g.index(1, 0, 0)], 1);
  // Without reading 2 the friction load does not come back: agent 0 keeps its 0.5.
  LoadTransfer sweep(g, kMaterial, coefficients(0.5, 0.5, 0.4, 1.0, 0.05), RuleSet::Patent);
  sweep.solve({{g.index(0, 0, 0), kMinusY, 1.0}});
  EXPECT_DOUBLE_EQ(face(sweep, 0, 0, kPlusY), 0.5);
}

TEST(AgentCyclic, APushedAgentPushesOnUnderReading2) {
  // Two agents side by side on a rigid base, 1 N down on the left one; alpha3 = 0 (no
  // friction), beta = 0.5, nu = 0.3: push factor (1 - beta) nu A/A = 0.15; poisson_decay 0.5,
  // gamma = 0.01.
  //   entry at 0: TOP0 0.5, down 0.25 to the base; pushes 0.15 * 0.5 = 0.075 out of the left
  //               side (passed out) and into agent 1 (both faces of the shared face).
  //   push at 1 (0.075): passed on 0.0375 out of the right side; reading 2: it pushes across
  //               with 0.15 * 0.075 = 0.01125, down onto the rigid base and up out of the top.
  const Grid g = plate(2, 1);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.0, 0.5, 0.01), RuleSet::Patent, with(true, false));
  m.solve({{g.index(0, 0, 0), kMinusY, 1.0}});
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kMinusY), 0.25);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusX), 0.075);
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kMinusX), 0.075);
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kMinusY), 0.01125);
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kPlusY), 0.0);  // the push up leaves through the free top
  const auto& d = m.diagnostics();
  EXPECT_DOUBLE_EQ(d.rigid_reaction, 0.25);
  EXPECT_DOUBLE_EQ(d.lateral_reaction, 0.01125);
  EXPECT_DOUBLE_EQ(d.lateral_passed_out, 0.075 + 0.0375 + 0.01125);
  EXPECT_DOUBLE_EQ(d.lost, 0.75);
  EXPECT_NEAR(balance_gap(d), 0.0, 1e-15);
}

TEST(AgentCyclic, BoundariesReturnTheLoadUnderReading6) {
  // One agent on a rigid base, 1 N down; alpha1 = alpha2 = 0.5, no friction, no push,
  // gamma = 0.05. The rigid base returns what reaches it, the free top reflects it:
  //   entry (1):         TOP(+y) 0.5; down 0.25 -> the base returns it, travelling up.
  //   up (0.25):         enters by the base: -y face 0.25; passes 0.125 up -> the free top
  //                      reflects it (the free face carries nothing).
  //   down (0.125):      passes 0.0625 down -> the base returns it.
  //   up (0.0625):       -y face += 0.0625; 0.03125 <= gamma dropped.
  const Grid g = plate(1, 1);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.0, 1.0, 0.05), RuleSet::Patent, with(false, true));
  m.solve({{0, kMinusY, 1.0}});
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kMinusY), 0.25 + 0.0625);
  const auto& d = m.diagnostics();
  EXPECT_EQ(d.rigid_reaction, 0.0);  // nothing leaves the body
  EXPECT_EQ(d.passed_out, 0.0);
  EXPECT_DOUBLE_EQ(d.returned_rigid, 0.25 + 0.0625);
  EXPECT_DOUBLE_EQ(d.returned_free, 0.125);
  EXPECT_DOUBLE_EQ(d.dropped, 0.03125);
  EXPECT_DOUBLE_EQ(d.lost, 0.75 + 0.125 + 0.0625 + 0.03125);
  EXPECT_NEAR(balance_gap(d), 0.0, 1e-15);
  EXPECT_EQ(d.agent_updates, 4u);
}

TEST(AgentCyclic, ReturnedFrictionTravelsBackUnderReading6Alone) {
  // A column of one agent over another (1 x 2), 1 N down on the top one; alpha1 = 0.5,
  // alpha2 = 0.2, alpha3 = 0.4, no push, gamma = 0.03. Without reading 2 a friction load goes
  // straight on; with reading 6 a free side returns it to the agent, which sends it on away from
  // that side: into the opposite free side, which returns it again.
  //   entry at top (1): TOP 0.5; down 0.1 to the lower agent; friction 0.4 to each side, both
  //                     returned (0.8 returned free).
  //   lower (0.1):      TOP 0.1; down 0.02 <= gamma dropped; friction 0.04 each side, returned.
  //   each friction at top (0.4): TOP 0.2; down 0.04 to the lower agent; friction 0.16 straight on
  //                     into the other side, returned.
  //   each friction at lower (0.04): TOP 0.02; down 0.004 dropped; friction 0.016 dropped.
  //   the lower agent, from the two downs of 0.04: TOP 0.08 in all; down 0.008 dropped; friction 0.016 dropped.
  //   each friction at top (0.16): TOP 0.08; down 0.016 dropped; friction 0.064, returned.
  //   each friction at top (0.064): TOP 0.032; down 0.0064 dropped; friction 0.0256 dropped.
  const Grid g = plate(1, 2);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.2, 0.4, 1.0, 0.03), RuleSet::Patent, with(false, true));
  m.solve({{g.index(0, 1, 0), kMinusY, 1.0}});
  EXPECT_DOUBLE_EQ(face(m, 0, 1, kPlusY), 0.5 + 2 * (0.2 + 0.08 + 0.032));
  EXPECT_DOUBLE_EQ(face(m, 0, 1, kMinusY), 0.1 + 2 * 0.04);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusY), 0.1 + 2 * 0.02 + 0.08);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kMinusY), 0.0);  // nothing above gamma reaches the base
  const auto& d = m.diagnostics();
  EXPECT_DOUBLE_EQ(d.returned_free, 0.8 + 0.08 + 2 * 0.16 + 2 * 0.064);
  EXPECT_EQ(d.returned_rigid, 0.0);
  EXPECT_NEAR(balance_gap(d), 0.0, 1e-15);
}

TEST(AgentCyclic, TheLoadBalanceHoldsWithRandomCoefficientsIn2DAnd3D) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(0.05, 0.6);
  for (int dim : {2, 3})
    for (int trial = 0; trial < 6; ++trial) {
      const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{7, 5, 1} : std::array<int, 3>{4, 4, 3};
      Grid g = Grid::box(dim, n, Eigen::Vector3d(1, 1.5, 0.8), 1.0);
      g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
      if (trial % 2) g.make_air(g.index(1, 1, 0));  // a hole: faces toward air inside the body
      Coefficients k = coefficients(unit(rng), unit(rng), unit(rng), unit(rng), 1e-3);
      k.poisson_decay = unit(rng);
      const Readings r = with(trial % 3 != 2, trial % 3 != 0);
      LoadTransfer m(g, kMaterial, k, RuleSet::Patent, r);
      const std::size_t entry = g.index(2, n[1] - 1, dim == 3 ? 1 : 0);
      m.solve({{entry, kMinusY, 2.0}, {g.index(3, 2, 0), kPlusX, 0.5}});
      const auto& d = m.diagnostics();
      const double scale = std::abs(d.rigid_reaction) + std::abs(d.passed_out) + d.dropped + std::abs(d.lost) + 2.5;
      EXPECT_NEAR(balance_gap(d), 0.0, 1e-13 * scale) << "dim " << dim << " trial " << trial;
      EXPECT_EQ(d.unfinished, 0.0);
      if (r.boundaries_return) {
        EXPECT_EQ(d.rigid_reaction, 0.0);
        EXPECT_EQ(d.passed_out, 0.0);
      }
      for (double f : m.face_forces()) EXPECT_GE(f, 0.0);
    }
}

TEST(AgentCyclic, RefusesWhatWouldNotEnd) {
  const Grid g = plate(3, 3);
  for (const Readings& r : {with(true, false), with(false, true)}) {
    EXPECT_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 0.5, 0.25, 0.5, 0.0), RuleSet::Patent, r),
                 std::invalid_argument);  // gamma = 0
    EXPECT_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 1.0, 0.25, 0.5, 1e-3), RuleSet::Patent, r),
                 std::invalid_argument);  // alpha2 = 1
    // alpha1 = 1 is allowed: it only ever multiplies alpha2 or a push factor.
    EXPECT_NO_THROW(LoadTransfer(g, kMaterial, coefficients(1.0, 0.5, 0.25, 0.5, 1e-3), RuleSet::Patent, r));
    EXPECT_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 0.5, 1.0, 0.5, 1e-3), RuleSet::Patent, r),
                 std::invalid_argument);  // alpha3 = 1
    Coefficients decay_one = coefficients(0.5, 0.5, 0.25, 0.5, 1e-3);
    decay_one.poisson_decay = 1.0;
    EXPECT_THROW(LoadTransfer(g, kMaterial, decay_one, RuleSet::Patent, r), std::invalid_argument);
    // A flat agent makes the push across it a factor above 1: (1 - 0) 0.3 A_x / A_y = 0.3 * 5.
    Grid flat = Grid::box(2, {3, 3, 1}, Eigen::Vector3d(0.2, 1, 1), 1.0);
    EXPECT_THROW(LoadTransfer(flat, kMaterial, coefficients(0.5, 0.5, 0.25, 0.0, 1e-3), RuleSet::Patent, r),
                 std::invalid_argument);
    EXPECT_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 0.5, 0.25, 0.5, 1e-3), RuleSet::Conserving, r),
                 std::invalid_argument);
    EXPECT_NO_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 0.5, 0.25, 0.5, 1e-3), RuleSet::Patent, r));
  }
  // Without these readings the same coefficients are accepted (the sweep has no cycles).
  EXPECT_NO_THROW(LoadTransfer(g, kMaterial, coefficients(0.5, 1.0, 0.25, 0.5, 0.0), RuleSet::Patent));
}

TEST(AgentCyclic, TheCapStopsLoudly) {
  // Factors near 1 and a tiny gamma: far more work than the cap allows; the result is refused.
  const Grid g = plate(9, 9);
  LoadTransfer m(g, kMaterial, coefficients(0.9, 0.9, 0.45, 0.5, 1e-9), RuleSet::Patent, with(true, true));
  std::vector<double> faces(g.count() * 4, 0.0);
  std::vector<std::int32_t> generation(g.count(), -1);
  Diagnostics d;
  EXPECT_THROW(cyclic_transfer(g, kMaterial, m.coefficients(), m.readings(), {{g.index(4, 8, 0), kMinusY, 1.0}},
                               faces, generation, d, 1000),
               CyclicCapReached);
  EXPECT_GT(d.unfinished, 0.0);
  EXPECT_LE(d.agent_updates, 1000u);
}

TEST(AgentCyclic, ACentredLoadGivesAMirrorSymmetricResult) {
  for (int dim : {2, 3}) {
    const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{9, 6, 1} : std::array<int, 3>{5, 4, 5};
    Grid g = Grid::box(dim, n, Eigen::Vector3d(1, 1, 1), 1.0);
    g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
    LoadTransfer m(g, kMaterial, coefficients(0.55, 0.5, 0.45, 0.5, 1e-3), RuleSet::Patent, with(true, true));
    const int kc = dim == 3 ? n[2] / 2 : 0;
    m.solve({{g.index(n[0] / 2, n[1] - 1, kc), kMinusY, 2.0}});
    const int nd = 2 * dim;
    double largest = 0;
    for (double f : m.face_forces()) largest = std::max(largest, f);
    ASSERT_GT(largest, 0.0);
    for (int k = 0; k < n[2]; ++k)
      for (int j = 0; j < n[1]; ++j)
        for (int i = 0; i < n[0]; ++i) {
          const std::size_t c = g.index(i, j, k), mirror = g.index(n[0] - 1 - i, j, k);
          const double* f = m.face_forces().data() + c * nd;
          const double* fm = m.face_forces().data() + mirror * nd;
          EXPECT_NEAR(f[kMinusX], fm[kPlusX], 1e-12 * largest);
          EXPECT_NEAR(f[kMinusY], fm[kMinusY], 1e-12 * largest);
          EXPECT_NEAR(f[kPlusY], fm[kPlusY], 1e-12 * largest);
          EXPECT_EQ(m.generation()[c], m.generation()[mirror]);
        }
  }
}

TEST(AgentCyclic, TheSweepsRulesInWorkListFormReproduceTheSweep) {
  // With readings 2 and 6 off the work-list runs the sweep's (acyclic) rules. With a gamma so
  // small that nothing is dropped both sum the same chains, so they agree to round-off.
  for (int dim : {2, 3}) {
    const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{6, 5, 1} : std::array<int, 3>{4, 3, 4};
    Grid g = Grid::box(dim, n, Eigen::Vector3d(1, 1.2, 0.9), 1.0);
    g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
    for (bool once : {false, true}) {
      Coefficients k = coefficients(0.6, 0.45, 0.3, 0.4, 1e-300);
      Readings r;
      r.non_compounding_entry = once;
      LoadTransfer sweep(g, kMaterial, k, RuleSet::Patent, r);
      const std::vector<EntryLoad> loads{{g.index(2, n[1] - 1, dim == 3 ? 2 : 0), kMinusY, 2.0}};
      sweep.solve(loads);
      std::vector<double> faces(sweep.face_forces().size(), 0.0);
      std::vector<std::int32_t> generation(g.count(), -1);
      Diagnostics d;
      cyclic_transfer(g, kMaterial, k, r, loads, faces, generation, d);
      for (std::size_t i = 0; i < faces.size(); ++i) EXPECT_NEAR(faces[i], sweep.face_forces()[i], 1e-13) << i;
      // The sweep leaves generation -1 on an agent inside a layer's loaded box that only a push
      // reaches (3D; its faces carry the push): the work-list marks every agent it updates.
      for (std::size_t c = 0; c < generation.size(); ++c) {
        if (sweep.generation()[c] >= 0) {
          EXPECT_EQ(generation[c], sweep.generation()[c]) << c;
        } else if (generation[c] >= 0) {
          EXPECT_EQ(dim, 3) << c;
        }
      }
      const auto& s = sweep.diagnostics();
      EXPECT_NEAR(d.rigid_reaction, s.rigid_reaction, 1e-13);
      EXPECT_NEAR(d.passed_out, s.passed_out, 1e-13);
      EXPECT_NEAR(d.lost, s.lost, 1e-13);
      EXPECT_NEAR(d.lateral_reaction, s.lateral_reaction, 1e-13);
      EXPECT_NEAR(d.lateral_passed_out, s.lateral_passed_out, 1e-13);
      EXPECT_EQ(d.dropped, 0.0);
      EXPECT_EQ(s.dropped, 0.0);
    }
  }
}

TEST(AgentCyclic, ReadingsOffLeaveTheSweepAsItWas) {
  // The readings' flags off: LoadTransfer is the sweep (pinned by test_load_transfer.cc); the
  // readings on change the result (they are dispatched, not ignored).
  const Grid g = plate(5, 4);
  const Coefficients k = coefficients(0.5, 0.5, 0.25, 0.5, 1e-3);
  LoadTransfer plain(g, kMaterial, k, RuleSet::Patent), off(g, kMaterial, k, RuleSet::Patent, with(false, false));
  plain.solve({{g.index(2, 3, 0), kMinusY, 2.0}});
  off.solve({{g.index(2, 3, 0), kMinusY, 2.0}});
  EXPECT_EQ(plain.face_forces(), off.face_forces());
  EXPECT_EQ(plain.diagnostics().agent_updates, off.diagnostics().agent_updates);
  LoadTransfer on(g, kMaterial, k, RuleSet::Patent, with(true, false));
  on.solve({{g.index(2, 3, 0), kMinusY, 2.0}});
  EXPECT_NE(plain.face_forces(), on.face_forces());
}
