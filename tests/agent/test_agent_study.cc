// The agent model as a study: case file -> mesh -> loads -> outputs.
#include <agent_study.h>

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "../support/scratch_folder.h"
#include "../support/study_error.h"

namespace fs = std::filesystem;

namespace {

const std::string kMeshes = WORKBENCH_SOURCE_DIR "/meshes/";

using test_support::write_file;

std::string plate_case(const std::string& boundary = "rigid = [\"base\"]", const std::string& direction = "-y",
                       const std::string& group = "load") {
  return "[mesh]\nfile = \"" + kMeshes + "plate2d.geo\"\n[mesh.parameters]\nh = 0.01\nlw = 0.02\n" +
         "[material]\nyoung = 206e9\npoisson = 0.3\nthickness = 0.002\n[boundary]\n" + boundary +
         "\n[[load]]\ngroup = \"" + group + "\"\ndirection = \"" + direction + "\"\nforce = 2.0\n" +
         "[agent]\nrule_set = \"conserving\"\ngamma = 1e-6\n[steps]\ncount = 3\n";
}

}  // namespace

TEST(AgentStudy, SeedPlateLoadIsSharedOverThePatchFaces) {
  workbench::CaseFile file(write_file("plate.toml", plate_case()));
  const auto study = agent_study::load_agent_study(file);
  ASSERT_EQ(study.loads.size(), 2u);
  for (const auto& l : study.loads) {
    EXPECT_DOUBLE_EQ(l.force, 1.0);
    EXPECT_EQ(l.dir, agent::direction(1, false));
  }
  EXPECT_DOUBLE_EQ(study.mesh.grid.thickness, 0.002);
  EXPECT_EQ(study.rules, agent::RuleSet::Conserving);
}

TEST(AgentStudy, DisplacementIsZeroOnTheBaseAndMirrorSymmetric) {
  workbench::CaseFile file(write_file("plate.toml", plate_case()));
  const auto study = agent_study::load_agent_study(file);
  auto model = agent_study::transfer_model(study);
  const auto s = agent_study::evaluate(study, model, 1.0);
  const auto& g = study.mesh.grid;
  // The conserving rule set returns the whole load at the rigid base.
  EXPECT_NEAR(s.diagnostics.rigid_reaction + s.diagnostics.passed_out + s.diagnostics.dropped, 2.0, 1e-12);
  double max_uy = 0;
  for (int j = 0; j <= 20; ++j)
    for (int i = 0; i <= 20; ++i) {
      const std::size_t n = g.node_index(i, j, 0), m = g.node_index(20 - i, j, 0);
      EXPECT_NEAR(s.displacement[2 * n], -s.displacement[2 * m], 1e-20);
      EXPECT_NEAR(s.displacement[2 * n + 1], s.displacement[2 * m + 1], 1e-20);
      if (j == 0) {
        EXPECT_EQ(s.displacement[2 * n + 1], 0.0);
      }
      max_uy = std::min(max_uy, s.displacement[2 * n + 1]);
    }
  // The plate is squeezed: the top under the load moves down, by 1e-9 m order for 2 N on steel.
  EXPECT_LT(max_uy, -1e-10);
  EXPECT_GT(max_uy, -1e-7);
}

TEST(AgentStudy, ImportsAMeshOnceWhateverTheLoadsAndCoefficients) {
  auto load = [](const std::string& text) {
    workbench::CaseFile file(write_file("cached.toml", text));
    return agent_study::load_agent_study(file);
  };
  auto replaced = [](std::string text, const std::string& from, const std::string& to) {
    return text.replace(text.find(from), from.size(), to);
  };
  const std::size_t before = agent_study::mesh_imports();
  const auto first = load(plate_case());
  const std::size_t after_first = agent_study::mesh_imports();
  EXPECT_LE(after_first, before + 1);  // (an earlier test of this process may have imported it)
  // Other loads, coefficients, rule set: the same grid, copied.
  const auto other = load(replaced(replaced(plate_case(), "force = 2.0", "force = 5.0"), "gamma = 1e-6",
                                   "gamma = 1e-3"));
  EXPECT_EQ(agent_study::mesh_imports(), after_first);
  EXPECT_EQ(other.mesh.grid.flags, first.mesh.grid.flags);
  EXPECT_EQ(other.mesh.cell_of_element, first.mesh.cell_of_element);
  EXPECT_DOUBLE_EQ(other.loads.front().force, 2.5);
  // Other mesh parameters: meshed again.
  load(replaced(plate_case(), "h = 0.01", "h = 0.005"));
  EXPECT_EQ(agent_study::mesh_imports(), after_first + 1);
  // The same name with other bytes: meshed again; a .geo that may read other files: every time.
  const std::string geo = test_support::read_file(kMeshes + "plate2d.geo");
  const std::string own = replaced(plate_case(), kMeshes + "plate2d.geo", (test_support::scratch_folder() / "own.geo").string());
  write_file("own.geo", geo);
  load(own);
  load(own);
  EXPECT_EQ(agent_study::mesh_imports(), after_first + 2);
  write_file("own.geo", geo + "// edited\n");
  load(own);
  EXPECT_EQ(agent_study::mesh_imports(), after_first + 3);
  write_file("own.geo", geo + "// Merge nothing\n");
  load(own);
  load(own);
  EXPECT_EQ(agent_study::mesh_imports(), after_first + 5);
}

TEST(AgentStudy, WritesEveryStepAndTheTables) {
  workbench::CaseFile file(write_file("plate.toml", plate_case()));
  const auto study = agent_study::load_agent_study(file);
  const fs::path dir = test_support::scratch_folder() / "out";
  fs::create_directories(dir);
  std::ostringstream log;
  agent_study::write_agent_outputs(study, dir, log);
  for (const char* f : {"agent.pvd", "agent_step_001.vtu", "agent_step_003.vtu", "agent_cells.csv", "agent_nodes.csv",
                        "agent_diagnostics.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  std::ifstream cells(dir / "agent_cells.csv");
  std::string line;
  int rows = -1;
  while (std::getline(cells, line)) ++rows;
  EXPECT_EQ(rows, 400);
  EXPECT_NE(log.str().find("step 3/3"), std::string::npos);
  // The conserving rule set returns the load at the base: no warning, the balance in the log.
  EXPECT_NE(log.str().find("step 3/3: load (0, -2) N"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find(" lost "), std::string::npos);
  EXPECT_EQ(log.str().find("warning"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "agent_summary.json"));
}

TEST(AgentStudy, LoadThatMissesTheRigidFaceWarnsAndMixedLoadsPrintVectors) {
  // The literal rules lose the load on the way down, and a side load never meets the base:
  // both runs finish, but say so in the log and in agent_summary.json.
  const std::string conserving = "rule_set = \"conserving\"";
  std::string patent = plate_case();
  patent.replace(patent.find(conserving), conserving.size(), "rule_set = \"patent\"");
  const std::string side = plate_case("rigid = [\"base\"]") +
                           "[[load]]\ngroup = \"free\"\ndirection = \"+x\"\nforce = 2.0\n";
  for (const bool mixed : {false, true}) {
    workbench::CaseFile file(write_file("warn.toml", mixed ? side : patent));
    const auto study = agent_study::load_agent_study(file);
    const fs::path dir = test_support::scratch_folder() / (mixed ? "mixed" : "patent");
    fs::create_directories(dir);
    std::ostringstream log;
    const auto warnings = agent_study::load_balance_warnings(agent_study::write_agent_outputs(study, dir, log).back().diagnostics);
    ASSERT_EQ(warnings.size(), 1u) << log.str();
    EXPECT_NE(warnings[0].find("reaches a rigid face"), std::string::npos);
    EXPECT_NE(log.str().find("agent: warning: only "), std::string::npos);
    std::ifstream summary(dir / "agent_summary.json");
    std::stringstream text;
    text << summary.rdbuf();
    EXPECT_NE(text.str().find(warnings[0]), std::string::npos);
    if (mixed) {
      EXPECT_NE(log.str().find("load (2, -2) N (4 N applied in all)"), std::string::npos) << log.str();
    }
  }
}

TEST(AgentStudy, BadCasesNameTheFileAndTheKey) {
  EXPECT_NE(test_support::study_error(plate_case("rigid = []")).find("boundary.rigid: no rigid faces"), std::string::npos);
  EXPECT_NE(test_support::study_error(plate_case("rigid = [\"floor\"]")).find("boundary.rigid: group 'floor' is not a physical group"),
            std::string::npos);
  EXPECT_NE(test_support::study_error(plate_case("rigid = [\"base\"]", "-z")).find("load[0].direction: -z is not an axis of a 2D mesh"),
            std::string::npos);
  EXPECT_NE(test_support::study_error(plate_case("rigid = [\"base\"]\nrollers = [\"free\"]")).find("boundary.rollers: the agent method"),
            std::string::npos);
  EXPECT_NE(test_support::study_error(plate_case() + "[mesh.extra]\n").find("unknown key"), std::string::npos);
  EXPECT_NE(test_support::study_error(plate_case() + "[output]\n").find("unknown key 'output'"), std::string::npos);
}
