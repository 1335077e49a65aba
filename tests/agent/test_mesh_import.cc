// Agents from gmsh meshes: the project's .geo files, and the meshes the method must refuse.
#include <agent/mesh_import.h>
#include <agent/voxelize.h>

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>
#include <string>

#include <unistd.h>

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
  // (Two squares 1e10 apart import as 3 x 3 slots; a box that would not fit is refused:
  // test_lattice.cc.)
  EXPECT_NE(import_error(kData + "graded.geo").find("same size"), std::string::npos) << import_error(kData + "graded.geo");
  EXPECT_NE(import_error(kMeshes + "plate2d.geo", {{"hh", 1.0}}).find("unknown mesh parameter 'hh'"), std::string::npos);
  EXPECT_NE(import_error(kMeshes + "plate2d.geo", {{"h", 0.003}}).find("must be multiples of h"), std::string::npos)
      << import_error(kMeshes + "plate2d.geo", {{"h", 0.003}});
  EXPECT_NE(import_error(kData + "missing.geo").find("no such mesh file"), std::string::npos);
}

TEST(MeshImport, AnLShapeLeavesItsMissingQuarterAsAirWithBoundaryFacesAround) {
  // Three unit squares of 2 x 2 agents each (h = 0.5) in an L: a 4 x 4 box, its upper right
  // 2 x 2 slots air.
  const auto m = import_mesh(kData + "l_shape.geo");
  ASSERT_EQ(m.grid.count(), 16u);
  EXPECT_EQ(m.grid.agent_count(), 12u);
  EXPECT_EQ(m.cell_of_element.size(), 12u);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) EXPECT_EQ(m.grid.is_air(m.grid.index(i, j, 0)), i >= 2 && j >= 2) << i << "," << j;
  // The boundary: 4 + 2 faces looking down and up, 4 + 2 looking left and right... 16 in all,
  // among them the two faces of each inner edge of the notch.
  EXPECT_EQ(m.grid.boundary_faces().size(), 16u);
  EXPECT_FALSE(m.grid.has_neighbour(m.grid.index(2, 1, 0), direction(1, true)));  // under the notch
  EXPECT_FALSE(m.grid.has_neighbour(m.grid.index(1, 2, 0), direction(0, true)));  // left of the notch
  const auto& base = m.face_groups.at("base");
  ASSERT_EQ(base.size(), 4u);
  for (const auto& f : base) {
    EXPECT_EQ(f.side, direction(1, false));
    EXPECT_EQ(m.grid.coords(f.cell)[1], 0);
  }
  const auto& load = m.face_groups.at("load");
  ASSERT_EQ(load.size(), 2u);
  for (const auto& f : load) {
    EXPECT_EQ(f.side, direction(1, true));
    EXPECT_EQ(m.grid.coords(f.cell)[1], 3);
    EXPECT_LT(m.grid.coords(f.cell)[0], 2);
  }
}

TEST(Voxelize, ADiscHasAboutPiRSquaredOverHSquaredAgents) {
  // Cells whose centre lies inside: the count can differ from pi r^2 / h^2 only by the cells
  // whose centre is within h / sqrt(2) of the rim (a ring of about 2 pi r sqrt(2) h / h^2 slots).
  for (double h : {0.2, 0.1, 0.05}) {
    const auto m = voxelize(kData + "disc.geo", h);
    const double expected = M_PI / (h * h), ring = 2 * M_PI * std::sqrt(2.0) / h;
    const double count = double(m.grid.agent_count());
    EXPECT_NEAR(count, expected, ring) << "h = " << h;
    EXPECT_NEAR(count, expected, 0.25 * ring) << "h = " << h;  // in practice well inside the ring
    EXPECT_EQ(m.cell_of_element.size(), m.grid.agent_count());
    // Every staircase boundary face lies next to the rim, and all of them are in "rim".
    const auto faces = m.grid.boundary_faces();
    EXPECT_EQ(m.face_groups.at("rim").size(), faces.size());
    for (const auto& f : faces) EXPECT_LT(std::abs(m.grid.centre(f.cell).norm() - 1.0), 1.5 * h) << f.cell;
  }
}

TEST(Voxelize, GroupsGoToTheNearestStaircaseFacesAndTheMshReadsBackIdentical) {
  namespace fs = std::filesystem;
  const fs::path msh = fs::temp_directory_path() / ("workbench_voxelize_" + std::to_string(::getpid()) + ".msh");  // removed at the end
  const double h = 0.005;
  const auto m = voxelize(kMeshes + "plate_hole.geo", h, {}, msh);
  const auto& g = m.grid;
  ASSERT_EQ(g.cells[0], 40);
  ASSERT_EQ(g.cells[1], 20);
  // The hole (R = 10 mm = 2 h at (0.1, 0.05), a lattice node) makes air of the 12 cells whose
  // centres lie within it: (+-0.5 h, +-0.5 h) and (+-1.5 h, +-0.5 h), (+-0.5 h, +-1.5 h).
  EXPECT_EQ(g.agent_count(), 800u - 12u);
  auto count_side = [&](const std::string& group, int side) {
    std::size_t n = 0;
    for (const auto& f : m.face_groups.at(group)) n += f.side == side;
    return n;
  };
  EXPECT_EQ(m.face_groups.at("fixed").size(), 20u);
  EXPECT_EQ(count_side("fixed", direction(0, false)), 20u);
  EXPECT_EQ(count_side("pull", direction(0, true)), 20u);
  EXPECT_EQ(m.face_groups.at("free").size(), 80u);
  for (const auto& f : m.face_groups.at("hole")) {
    const Eigen::Vector3d c = g.centre(f.cell) - Eigen::Vector3d(0.1, 0.05, 0);
    EXPECT_LT(c.head<2>().norm(), 0.01 + h) << f.cell;
    EXPECT_GT(c.head<2>().norm(), 0.01 - h) << f.cell;
  }
  // The staircase's boundary: the outer 120 faces and the hole's rim, a 4 x 4 square of air
  // without its corners (the cells centred (1.5 h, 1.5 h) from the centre lie outside R = 2 h):
  // cutting corners off a square keeps its perimeter, 16 faces.
  EXPECT_EQ(m.face_groups.at("hole").size(), 16u);
  EXPECT_EQ(g.boundary_faces().size(), 136u);
  // The written .msh is the same grid with the same groups.
  const auto back = import_mesh(msh);
  EXPECT_EQ(back.grid.cells, g.cells);
  EXPECT_EQ(back.grid.flags, g.flags);
  for (const auto& [name, faces] : m.face_groups) {
    ASSERT_EQ(back.face_groups.at(name).size(), faces.size()) << name;
    std::set<std::pair<std::size_t, int>> a, b;
    for (const auto& f : faces) a.insert({f.cell, f.side});
    for (const auto& f : back.face_groups.at(name)) b.insert({f.cell, f.side});
    EXPECT_EQ(a, b) << name;
  }
  fs::remove(msh);
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
