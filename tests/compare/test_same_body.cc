// The same-body check (compare/same_body.h): the shapes of both kinds of mesh against hand-computed
// values, and what the check refuses, lets pass and warns about.
#include <agent/mesh_import.h>
#include <compare/same_body.h>
#include <workbench/error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

using namespace compare;

namespace {

const double kPi = 3.14159265358979323846;

// The seed plate, 200 x 200 mm, 10 mm agents, the 20 mm load patch in the middle of its top edge.
agent::ImportedMesh plate() {
  return agent::import_mesh(WORKBENCH_SOURCE_DIR "/meshes/plate2d.geo", {{"h", 0.01}, {"lw", 0.02}});
}

}  // namespace

TEST(SameBody, AgentsShape) {
  const auto s = shape_of_agents(plate());
  EXPECT_EQ(s.dim, 2);
  EXPECT_NEAR(s.measure, 0.04, 1e-12);   // 400 agents of 1e-4 m^2
  EXPECT_NEAR(s.boundary, 0.8, 1e-12);   // the square's perimeter
  EXPECT_NEAR(s.hi.x(), 0.2, 1e-12);
  EXPECT_NEAR(s.hi.y(), 0.2, 1e-12);
  const auto& load = s.groups.at("load");  // two faces, x in [0.09, 0.11] at y = 0.2
  EXPECT_NEAR(load.measure, 0.02, 1e-12);
  EXPECT_NEAR(load.centroid.x(), 0.1, 1e-12);
  EXPECT_NEAR(load.centroid.y(), 0.2, 1e-12);
  EXPECT_NEAR(load.lo.x(), 0.09, 1e-12);
  EXPECT_NEAR(load.hi.x(), 0.11, 1e-12);
  EXPECT_NEAR(s.groups.at("base").measure, 0.2, 1e-12);
}

TEST(SameBody, MeshShapeInItsUnit) {
  // The unit disc (triangles of 0.02) read as millimetres: its rim is a polygon of n = 316 chords
  // (2 pi / 0.02 = 314.2, rounded up by gmsh's curve mesher), area n/2 sin(2 pi / n) mm^2, perimeter
  // 2 n sin(pi / n) mm, centred on the origin.
  const auto s = shape_of_mesh(WORKBENCH_SOURCE_DIR "/tests/data/disc.geo", {}, 1e-3);
  const double n = 316;
  EXPECT_EQ(s.dim, 2);
  EXPECT_NEAR(s.measure, n / 2 * std::sin(2 * kPi / n) * 1e-6, 1e-15);
  EXPECT_NEAR(s.lo.x(), -1e-3, 1e-12);
  EXPECT_NEAR(s.hi.y(), 1e-3, 1e-12);
  const auto& rim = s.groups.at("rim");
  EXPECT_NEAR(rim.measure, 2 * n * std::sin(kPi / n) * 1e-3, 1e-14);
  EXPECT_NEAR(rim.centroid.norm(), 0, 1e-9);
}

namespace {

// Checks `agents` against the plate's own shape as the reference (agent size 10 mm).
std::vector<std::string> check_against_plate(const BodyShape& agents) {
  workbench::CaseFile file("[mesh]\nfile = \"plate.msh\"\n[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\nforce = 2.0\n",
                           "case.toml");
  const auto setup = workbench::read_study_setup(file.root());
  return check_same_body(file, "compare.reference.mesh", setup, 0.01, agents, shape_of_agents(plate()), "plate.geo");
}

std::string refusal(const BodyShape& agents) {
  try {
    check_against_plate(agents);
  } catch (const workbench::Error& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SameBody, WithinAnAgentSizePasses) {
  auto agents = shape_of_agents(plate());
  EXPECT_TRUE(check_against_plate(agents).empty());
  agents.groups["load"].centroid.x() += 0.0099;  // less than one 10 mm agent: the staircase's freedom
  agents.groups["load"].lo.x() += 0.0099;
  agents.groups["load"].hi.x() += 0.0099;
  EXPECT_TRUE(check_against_plate(agents).empty());
}

TEST(SameBody, MovedLoadIsRefusedWithBothPositions) {
  auto agents = shape_of_agents(plate());
  agents.groups["load"].centroid.x() = 0.05;
  EXPECT_EQ(refusal(agents).rfind("case.toml: compare.reference.mesh: load[0].group 'load': its centre is (0.05, 0.2) in "
                                  "the agents' mesh and (0.1, 0.2) in the reference's, more than an agent size (10 mm) apart",
                                  0),
            0u)
      << refusal(agents);
}

TEST(SameBody, MovedSupportBodyAndMissingGroupAreRefused) {
  auto agents = shape_of_agents(plate());
  agents.groups["base"].hi.x() = 0.18;  // the support 20 mm short
  EXPECT_NE(refusal(agents).find("boundary.rigid group 'base': its upper corner is (0.18, 0) in the agents' mesh and (0.2, 0)"),
            std::string::npos)
      << refusal(agents);
  agents = shape_of_agents(plate());
  agents.hi.y() = 0.4;  // twice as tall
  EXPECT_NE(refusal(agents).find("the body's bounding box is (0, 0) to (0.2, 0.4)"), std::string::npos) << refusal(agents);
  agents = shape_of_agents(plate());
  agents.measure = 0.04 + 0.8 * 0.01 * 1.01;  // more than the perimeter times an agent size
  EXPECT_NE(refusal(agents).find("the body's area is"), std::string::npos) << refusal(agents);
}

TEST(SameBody, PatchAreaWarns) {
  auto agents = shape_of_agents(plate());
  agents.groups["load"].measure = 0.018;  // 18 mm against 20: -10 %, the pressure 1/0.9 - 1 = +11.1 %
  const auto warnings = check_against_plate(agents);
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("length 0.018 m, the true patch 0.02 m (-10 %); the force stays the case's 2 N, so the "
                             "agents' pressure on it is 11.1 % off"),
            std::string::npos)
      << warnings[0];
  agents.groups["load"].measure = 0.0195;  // -2.5 %: below the warning's 3 %
  EXPECT_TRUE(check_against_plate(agents).empty());
}
