// Agents from gmsh meshes: the project's .geo files, and the meshes the method must refuse.
#include <agent/mesh_import.h>

#include <gtest/gtest.h>

#include <string>

using namespace agent;

namespace {
const std::string kMeshes = WORKBENCH_SOURCE_DIR "/meshes/";
const std::string kData = WORKBENCH_SOURCE_DIR "/tests/data/";

std::string import_error(const std::string& file, const std::map<std::string, double>& parameters = {}) {
  try {
    import_mesh(file, parameters);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "no error";
}
}  // namespace

TEST(MeshImport, SeedPlateIsAGridOfSquaresWithItsGroups) {
  const auto m = import_mesh(kMeshes + "plate2d.geo", {{"h", 0.01}, {"lw", 0.02}});
  EXPECT_EQ(m.grid.dim, 2);
  EXPECT_EQ(m.grid.cells[0], 20);
  EXPECT_EQ(m.grid.cells[1], 20);
  EXPECT_NEAR(m.grid.size[0], 0.01, 1e-12);
  EXPECT_NEAR(m.grid.origin[1], 0.0, 1e-12);
  ASSERT_EQ(m.cell_of_element.size(), 400u);
  EXPECT_EQ(m.face_groups.at("base").size(), 20u);
  EXPECT_EQ(m.face_groups.at("free").size(), 20u + 20u + 18u);
  const auto& load = m.face_groups.at("load");
  ASSERT_EQ(load.size(), 2u);
  for (const auto& f : load) {
    EXPECT_EQ(f.side, direction(1, true));
    const auto c = m.grid.coords(f.cell);
    EXPECT_EQ(c[1], 19);
    EXPECT_TRUE(c[0] == 9 || c[0] == 10);
  }
  // Every cell appears exactly once.
  std::vector<int> seen(400, 0);
  for (auto c : m.cell_of_element) ++seen[c];
  for (int s : seen) EXPECT_EQ(s, 1);
  EXPECT_NE(std::find(m.parameters.begin(), m.parameters.end(), "h"), m.parameters.end());
}

TEST(MeshImport, BlockIsAGridOfCubesWithItsGroups) {
  const auto m = import_mesh(kMeshes + "block3d.geo", {{"h", 0.004}, {"lw", 0.008}});
  EXPECT_EQ(m.grid.dim, 3);
  EXPECT_EQ(m.grid.cells[0], 10);
  EXPECT_EQ(m.grid.cells[1], 10);
  EXPECT_EQ(m.grid.cells[2], 10);
  EXPECT_EQ(m.face_groups.at("base").size(), 100u);
  EXPECT_EQ(m.face_groups.at("load").size(), 4u);
  EXPECT_EQ(m.face_groups.at("free").size(), 600u - 100u - 4u);
}

TEST(MeshImport, RefusesWhatTheMethodCannotUse) {
  EXPECT_NE(import_error(kData + "triangles.geo").find("Triangle"), std::string::npos) << import_error(kData + "triangles.geo");
  EXPECT_NE(import_error(kData + "l_shape.geo").find("hole in the tiling at (1.25, 1.25)"), std::string::npos)
      << import_error(kData + "l_shape.geo");
  EXPECT_NE(import_error(kData + "graded.geo").find("same size"), std::string::npos) << import_error(kData + "graded.geo");
  EXPECT_NE(import_error(kMeshes + "plate2d.geo", {{"hh", 1.0}}).find("unknown mesh parameter 'hh'"), std::string::npos);
  EXPECT_NE(import_error(kMeshes + "plate2d.geo", {{"h", 0.003}}).find("must be multiples of h"), std::string::npos)
      << import_error(kMeshes + "plate2d.geo", {{"h", 0.003}});
  EXPECT_NE(import_error(kData + "missing.geo").find("no such mesh file"), std::string::npos);
}

TEST(MeshImport, RefusesOverlapsIncoherentNodesAndBrokenMshFiles) {
  // Two unit squares side by side (MSH 2.2), each file with one fault.
  EXPECT_EQ(import_error(kData + "overlap.msh"), kData + "overlap.msh: elements 1 and 3 overlap at (0, 0)");
  EXPECT_EQ(import_error(kData + "incoherent.msh"),
            kData + "incoherent.msh: nodes 2 and 7 coincide at (1, 0); neighbouring agents must share nodes (Coherence)");
  // Checked before gmsh reads the file (gmsh 4.8 crashed on the tag, took the NaN and the copy).
  EXPECT_EQ(import_error(kData + "duplicated.msh"),
            kData + "duplicated.msh: elements 2 and 3 are the same element (duplicated: same type, same nodes)");
  EXPECT_EQ(import_error(kData + "nan_node.msh"), kData + "nan_node.msh: node 3 has a non-finite coordinate");
  EXPECT_NE(import_error(kData + "negative_tag.msh").find("bad element node tag '-105'"), std::string::npos);
}
