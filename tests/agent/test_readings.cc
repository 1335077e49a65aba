// The patent rule set's seed readings (docs/agent-model.md, "Readings"), each on a tiny grid
// against hand-computed numbers, with the load balance.
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent_study.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../support/agent_fixtures.h"
#include "../support/scratch_folder.h"

using namespace agent;
using namespace test_support;  // plate, face, coefficients, kMaterial, the face directions

namespace {

Readings only(bool Readings::*r) {
  Readings x;
  x.*r = true;
  return x;
}

void expect_load_balance(const Diagnostics& d) {
  EXPECT_NEAR(d.applied, d.rigid_reaction + d.passed_out + d.dropped + d.lost, 1e-15);
}

}  // namespace

TEST(AgentReadings, NonCompoundingEntryPassesAlpha2OfTheWholeLoad) {
  const Grid g = plate(5, 4);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.0, 1.0, 0.0), RuleSet::Patent,
                 only(&Readings::non_compounding_entry));
  m.solve({{g.index(2, 3, 0), direction(1, false), 1.0}});
  // P1 = alpha1 P0 = 0.5 on the entry's top, P2 = alpha2 P0 = 0.5 below (not alpha2 alpha1 P0 = 0.25).
  EXPECT_DOUBLE_EQ(face(m, 2, 3, kPlusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 2, 3, kMinusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 2, 2, kPlusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 2, 1, kPlusY), 0.25);
  EXPECT_DOUBLE_EQ(face(m, 2, 0, kPlusY), 0.125);
  EXPECT_DOUBLE_EQ(m.diagnostics().rigid_reaction, 0.0625);
  // Lost: 1 - alpha2 of each agent's input, 0.5 + 0.25 + 0.125 + 0.0625.
  EXPECT_DOUBLE_EQ(m.diagnostics().lost, 0.9375);
  expect_load_balance(m.diagnostics());
  // Reading 4 on a one-agent entry: the entry agent's stress is alpha1 P0 / A = 0.500 P0/A
  // (the mean of its faces would give 0.5 (0.5 + 0.5) = 0.5 here too, and 0.375 without reading 1).
  Readings both = only(&Readings::non_compounding_entry);
  both.entering_face_stress = true;
  const auto sigma = agent_stresses(g, m.face_forces(), both, kMinusY, 1.0, 0.3);
  EXPECT_DOUBLE_EQ(sigma[2 * g.index(2, 3, 0) + 1], -0.5);
  EXPECT_DOUBLE_EQ(sigma[2 * g.index(2, 2, 0) + 1], -0.5);
  EXPECT_DOUBLE_EQ(sigma[2 * g.index(2, 1, 0) + 1], -0.25);
}

TEST(AgentReadings, NonCompoundingEntryLetsFrictionGoOnWithAlpha2WithoutAlpha1) {
  const Grid g = plate(3, 2);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.25, 1.0, 0.0), RuleSet::Patent,
                 only(&Readings::non_compounding_entry));
  m.solve({{g.index(1, 1, 0), direction(1, false), 1.0}});
  // Row 1: friction P3 = alpha3 P0 = 0.25 enters each side agent whole and goes down as
  // alpha2 P3 = 0.125; alpha3 P3 = 0.0625 leaves each free side.
  EXPECT_DOUBLE_EQ(face(m, 0, 1, kPlusY), 0.25);
  EXPECT_DOUBLE_EQ(face(m, 0, 1, kMinusY), 0.125);
  EXPECT_DOUBLE_EQ(face(m, 1, 1, kPlusY), 0.5);
  EXPECT_DOUBLE_EQ(face(m, 1, 1, kMinusY), 0.5);
  // Row 0, from above 0.125, 0.5, 0.125. The friction arriving at the middle from each side is
  // alpha3 0.125 = 0.03125; at a side agent from the far side, alpha3 (0.03125 + 0.5) = 0.1328125.
  EXPECT_DOUBLE_EQ(face(m, 1, 0, kPlusY), 0.5 + 2 * 0.03125);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kPlusY), 0.125 + 0.1328125);
  EXPECT_DOUBLE_EQ(face(m, 0, 0, kMinusY), 0.5 * (0.125 + 0.1328125));
  EXPECT_DOUBLE_EQ(m.diagnostics().rigid_reaction, 0.5 * (0.5625 + 2 * 0.2578125));
  // Passed out at the free sides: 0.0625 each in row 1, alpha3 (0.1328125 + 0.125) each in row 0.
  EXPECT_DOUBLE_EQ(m.diagnostics().passed_out, 2 * 0.0625 + 2 * 0.064453125);
  expect_load_balance(m.diagnostics());
}

TEST(AgentReadings, WithoutReadingsTheStressesAreTheMeanOfTheFaces) {
  Grid g = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(0.5, 0.25, 1), 0.1);
  const std::vector<double> f{1.0, 3.0, 2.0, 4.0};
  EXPECT_EQ(agent_stresses(g, f, Readings{}, kMinusY, 0.5, 0.3), agent_stresses(g, f));
}

TEST(AgentReadings, EnteringFaceStressIsTheTopFaceOverItsArea) {
  Grid g = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(0.5, 0.25, 1), 0.1);
  const std::vector<double> f{1.0, 3.0, 2.0, 4.0};  // -x, +x, -y, +y
  const auto down = agent_stresses(g, f, only(&Readings::entering_face_stress), kMinusY, 0.5, 0.3);
  EXPECT_DOUBLE_EQ(down[1], -4.0 / (0.5 * 0.1));  // a load moving -y enters by the +y face
  EXPECT_DOUBLE_EQ(down[0], -2.0 / (0.25 * 0.1));  // across the load: unchanged, the mean
  const auto right = agent_stresses(g, f, only(&Readings::entering_face_stress), kPlusX, 0.5, 0.3);
  EXPECT_DOUBLE_EQ(right[0], -1.0 / (0.25 * 0.1));  // a load moving +x enters by the -x face
  EXPECT_DOUBLE_EQ(right[1], -3.0 / (0.5 * 0.1));
}

TEST(AgentReadings, LateralStrainStressIsTensionMinusBetaNuSigmaAlong) {
  for (int dim : {2, 3}) {
    Grid g = Grid::box(dim, {1, 1, 1}, Eigen::Vector3d(0.5, 0.25, 2.0), 0.1);
    std::vector<double> f(2 * dim, 0.0);
    f[kMinusY] = 2.0;
    f[kPlusY] = 4.0;
    f[kMinusX] = 7.0;  // a push across: ignored under this reading
    const auto s = agent_stresses(g, f, only(&Readings::lateral_strain_stress), kMinusY, 0.5, 0.3);
    const double sigma_y = -3.0 / g.face_area(1);
    EXPECT_DOUBLE_EQ(s[1], sigma_y);
    EXPECT_DOUBLE_EQ(s[0], -0.5 * 0.3 * sigma_y);
    EXPECT_GT(s[0], 0.0);  // tension
    if (dim == 3) {
      EXPECT_DOUBLE_EQ(s[2], -0.5 * 0.3 * sigma_y);
    }
  }
  // Both stress readings: the lateral stress follows the entering-face stress.
  Grid g = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(1, 1, 1), 1.0);
  Readings both;
  both.entering_face_stress = both.lateral_strain_stress = true;
  const auto s = agent_stresses(g, {0.0, 0.0, 2.0, 4.0}, both, kMinusY, 0.5, 0.3);
  EXPECT_DOUBLE_EQ(s[1], -4.0);
  EXPECT_DOUBLE_EQ(s[0], 0.6);
}

namespace {
std::string seed_plate_with(const std::string& readings) {
  std::ifstream in(WORKBENCH_SOURCE_DIR "/cases/seed_plate.toml");
  std::stringstream text;
  text << in.rdbuf();
  std::string body = text.str();
  const std::string mesh = "\"../meshes/plate2d.geo\"";
  body.replace(body.find(mesh), mesh.size(), "\"" WORKBENCH_SOURCE_DIR "/meshes/plate2d.geo\"");
  body.insert(body.find("[agent]\n") + 8, "readings = [" + readings + "]\n");
  return body;
}
// The reader's one-line error for a case file's text ("no error" when it loads).
std::string error(const std::string& body) {
  try {
    workbench::CaseFile file(test_support::write_file("case.toml", body));
    agent_study::load_agent_study(file);
  } catch (const workbench::Error& e) {
    return std::string(e.what());
  }
  return std::string("no error");
}
}  // namespace

TEST(AgentReadings, SeedPlateLoadedAgentUnderEnteringFaceStress) {
  // The patch is two agents. Each takes its own entry alpha1 P0 on its top and the friction
  // alpha3 P0 = 0.25 P0 of the other entry: whole under reading 1 (0.5 + 0.25 = 0.75 P0/A),
  // with alpha1 under the old entry (0.5 + 0.125 = 0.625 P0/A).
  for (const auto& [readings, expected] : {std::pair<std::string, double>{"\"non_compounding_entry\", \"entering_face_stress\"", 0.75},
                                           {"\"entering_face_stress\"", 0.625}}) {
    workbench::CaseFile file(test_support::write_file("seed.toml", seed_plate_with(readings)));
    const auto study = agent_study::load_agent_study(file);
    ASSERT_TRUE(study.readings.entering_face_stress);
    auto model = agent_study::transfer_model(study);
    const auto s = agent_study::evaluate(study, model, 1.0);
    const auto& g = study.mesh.grid;
    ASSERT_EQ(study.loads.size(), 2u);
    const double p0_over_a = 2.0 / (2 * g.face_area(1));  // 2 N over the two-agent patch
    for (const auto& l : study.loads) EXPECT_NEAR(-s.stress[l.cell][workbench::kYY] / p0_over_a, expected, 1e-12) << readings;
    expect_load_balance(s.diagnostics);
  }
}

TEST(AgentReadings, CaseFileRejectsUnknownReadingsAndEntryReadingOfConserving) {
  EXPECT_NE(error(seed_plate_with("\"curvy\"")).find("agent.readings: unknown reading \"curvy\""), std::string::npos);
  std::string conserving = seed_plate_with("\"non_compounding_entry\"");
  conserving.replace(conserving.find("rule_set = \"patent\""), 19, "rule_set = \"conserving\"");
  EXPECT_NE(error(conserving).find("agent.readings: non_compounding_entry is a reading of the patent rule set"),
            std::string::npos);
}

TEST(AgentReadings, CaseFileTakesTheCyclicReadingsAndRefusesWhatWouldNotEnd) {
  const std::string both = "\"every_agent_all_operations\", \"boundaries_return\"";
  {
    workbench::CaseFile file(test_support::write_file("seed.toml", seed_plate_with(both)));
    const auto study = agent_study::load_agent_study(file);
    EXPECT_TRUE(study.readings.every_agent_all_operations);
    EXPECT_TRUE(study.readings.boundaries_return);
    EXPECT_EQ(agent_study::names_of(study.readings),
              (std::vector<std::string>{"every_agent_all_operations", "boundaries_return"}));
    auto model = agent_study::transfer_model(study);
    const auto s = agent_study::evaluate(study, model, 1.0);
    EXPECT_NEAR(s.diagnostics.applied,
                s.diagnostics.rigid_reaction + s.diagnostics.passed_out + s.diagnostics.dropped + s.diagnostics.lost,
                1e-12 * (s.diagnostics.dropped + std::abs(s.diagnostics.lost)));
    EXPECT_EQ(s.diagnostics.rigid_reaction, 0.0);  // reading 6: nothing leaves the body
    EXPECT_EQ(s.diagnostics.passed_out, 0.0);
    EXPECT_GT(s.diagnostics.returned_free, 0.0);  // the top and the sides reflect (the base is out of reach)
  }
  for (const char* other : {"conserving", "directional"}) {
    std::string body = seed_plate_with(both);
    body.replace(body.find("rule_set = \"patent\""), 19, std::string("rule_set = \"") + other + "\"");
    EXPECT_NE(error(body).find("agent.readings: every_agent_all_operations and boundaries_return are readings of the "
                               "patent rule set"),
              std::string::npos)
        << other;
  }
  std::string no_gamma = seed_plate_with("\"boundaries_return\"");
  no_gamma.replace(no_gamma.find("gamma = 1.0e-3"), 14, "gamma = 0.0");
  EXPECT_NE(error(no_gamma).find("agent.gamma: readings every_agent_all_operations / boundaries_return need gamma > 0"),
            std::string::npos)
      << error(no_gamma);
  std::string alpha2_one = seed_plate_with("\"every_agent_all_operations\"");
  alpha2_one.replace(alpha2_one.find("alpha2 = 0.5"), 12, "alpha2 = 1.0");
  EXPECT_NE(error(alpha2_one).find("agent.readings: readings every_agent_all_operations / boundaries_return need every "
                                   "transfer factor below 1 (the cyclic transfer would not end): alpha2 = 1"),
            std::string::npos)
      << error(alpha2_one);
}
