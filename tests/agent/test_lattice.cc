// The compressed lattice: memory follows the occupied lattice planes, positions stay true, and the
// transfer sees the same body as on the uncompressed box.
#include <agent/load_transfer.h>
#include <agent/mesh_import.h>
#include <agent/voxelize.h>
#include <agent_study.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>

#include "../support/agent_fixtures.h"
#include "../support/scratch_folder.h"

using namespace agent;

namespace {

const std::string kData = WORKBENCH_SOURCE_DIR "/tests/data/";
using test_support::kMaterial;
using test_support::kMinusY;
using test_support::kPlusY;

// The entry loads of a group of faces: `force` per face, pushing into the body, in grid order
// (loads superpose: the same order gives the same sums, bit for bit).
std::vector<EntryLoad> loads_on(const std::vector<BoundaryFace>& faces, double force) {
  std::vector<EntryLoad> out;
  for (const auto& f : faces) out.push_back({f.cell, opposite(f.side), force});
  std::sort(out.begin(), out.end(), [](const EntryLoad& a, const EntryLoad& b) { return a.cell < b.cell; });
  return out;
}

LoadTransfer solved(const Grid& g, RuleSet rules, const std::vector<EntryLoad>& loads) {
  const Coefficients k = rules == RuleSet::Directional ? Coefficients{} : test_support::coefficients(0.9, 0.8, 0.15, 0.5, 1e-9);
  LoadTransfer m(g, kMaterial, k, rules);
  m.solve(loads);
  return m;
}

// The face forces of the agent at box coordinates `c`.
std::vector<double> faces_at(const LoadTransfer& m, std::array<int, 3> c) {
  const auto& g = m.grid();
  const std::size_t nd = 2 * g.dim, cell = g.index(c[0], c[1], c[2]);
  return {m.face_forces().begin() + cell * nd, m.face_forces().begin() + (cell + 1) * nd};
}

}  // namespace

TEST(CompressedLattice, ARunOfEmptyPlanesIsOneAirSlotAndOneEmptyPlaneStays) {
  // Occupied 0, 1, 5, 7, 9: slots [0,1) [1,2) agents, [2,5) one air slot for three empty planes,
  // [5,6), [6,7) one empty plane kept as it is, [7,8), [8,9), [9,10).
  const CompressedAxis axis({9, 1, 0, 5, 7, 5});
  EXPECT_EQ(axis.first, (std::vector<std::int64_t>{0, 1, 2, 5, 6, 7, 8, 9, 10}));
  EXPECT_EQ(axis.slots(), 8u);
  EXPECT_EQ(axis.slot(5), 3u);
  EXPECT_EQ(axis.slot(3), 2u);
  EXPECT_EQ(axis.slot(9), 7u);
  EXPECT_TRUE(axis.collapsed());
  EXPECT_FALSE(CompressedAxis({0, 2, 1, 4}).collapsed());  // single empty planes: the uniform lattice
}

TEST(CompressedLattice, TwoSquares1e10ApartAreThreeByThreeSlotsAtTheirTruePlaces) {
  // far_apart.geo: unit squares at (0, 0) and (1e10, 1e10), base of the first one rigid-able.
  const auto m = import_mesh(kData + "far_apart.geo");
  const Grid& g = m.grid;
  ASSERT_EQ(g.cells, (std::array<int, 3>{3, 3, 1}));
  EXPECT_EQ(g.agent_count(), 2u);
  EXPECT_TRUE(g.is_air(g.index(1, 1, 0)));
  EXPECT_EQ(m.cell_of_element, (std::vector<std::size_t>{g.index(0, 0, 0), g.index(2, 2, 0)}));
  EXPECT_EQ(g.centre(g.index(0, 0, 0)), Eigen::Vector3d(0.5, 0.5, 0));
  EXPECT_EQ(g.centre(g.index(2, 2, 0)), Eigen::Vector3d(1e10 + 0.5, 1e10 + 0.5, 0));
  EXPECT_EQ(g.centre(g.index(1, 1, 0)), Eigen::Vector3d(0.5e10 + 0.5, 0.5e10 + 0.5, 0));  // the gap's middle
  EXPECT_EQ(g.node_position(1, 0, 0), Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(g.node_position(2, 3, 0), Eigen::Vector3d(1e10, 1e10 + 1, 0));
  EXPECT_DOUBLE_EQ(g.slot_coordinate(0, 1e10 + 0.25), 2.25);
  EXPECT_DOUBLE_EQ(g.position(0, 2.25), 1e10 + 0.25);
  EXPECT_EQ(m.face_groups.at("base").size(), 1u);

  // Solved: each square as it is alone (the first on its rigid base, the second free).
  Grid with_base = g;
  with_base.set_boundary(m.face_groups.at("base"), Boundary::Rigid);
  Grid alone_rigid = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(1, 1, 1));
  alone_rigid.set_boundary(alone_rigid.box_side(kMinusY), Boundary::Rigid);
  const Grid alone_free = Grid::box(2, {1, 1, 1}, Eigen::Vector3d(1, 1, 1));
  for (RuleSet rules : {RuleSet::Patent, RuleSet::Conserving, RuleSet::Directional}) {
    const auto both = solved(with_base, rules,
                             {{g.index(0, 0, 0), direction(1, false), 2.0}, {g.index(2, 2, 0), direction(1, false), 3.0}});
    EXPECT_EQ(faces_at(both, {0, 0, 0}), faces_at(solved(alone_rigid, rules, {{0, direction(1, false), 2.0}}), {0, 0, 0}));
    EXPECT_EQ(faces_at(both, {2, 2, 0}), faces_at(solved(alone_free, rules, {{0, direction(1, false), 3.0}}), {0, 0, 0}));
    EXPECT_DOUBLE_EQ(both.diagnostics().applied, 5.0);
    // Memory: 9 slots of 4 face forces (8 B), a generation (4 B) and a flag (1 B) = 333 B, the
    // four per-layer scratch arrays of at most 3 doubles (96 B), and the touched-layer list: one
    // entry (24 B) per load and row it reaches, 2 here. The directional rule set: a shear per slot
    // (8 B) and two moment-balance slopes per layer across each axis (2 x (3 + 3 + 1) x 8 B)
    // instead of the scratch.
    EXPECT_LE(both.memory_bytes(), rules == RuleSet::Directional ? 333u + 9u * 8u + 14u * 8u : 333u + 96u + 2u * 24u);
  }
}

TEST(CompressedLattice, TwoPlates1mApartAt1mmSolveAsEachAlone) {
  const auto m = import_mesh(kData + "two_plates.geo");
  const Grid& g = m.grid;
  ASSERT_EQ(g.cells, (std::array<int, 3>{21, 5, 1}));  // 10 + 1 air + 10 columns, not 1020
  EXPECT_EQ(g.agent_count(), 100u);
  EXPECT_EQ(g.planes[0].size(), 22u);
  EXPECT_TRUE(g.planes[1].empty());  // no empty row: y stays uniform
  // Positions to within gmsh's rounding of its nodes (the agent size is read from an element).
  EXPECT_NEAR(g.plane(0, 10), 0.010, 1e-12);
  EXPECT_NEAR(g.plane(0, 11), 1.010, 1e-12);
  EXPECT_NEAR(g.plane(0, 21), 1.020, 1e-12);
  EXPECT_NEAR(g.centre(g.index(11, 2, 0))[0], 1.0105, 1e-12);
  EXPECT_NEAR(g.centre(g.index(11, 2, 0))[1], 0.0025, 1e-12);
  EXPECT_EQ(m.face_groups.at("top_b").size(), 10u);

  Grid body = g;
  body.set_boundary(m.face_groups.at("base"), Boundary::Rigid);
  Grid alone = Grid::box(2, {10, 5, 1}, g.size);
  alone.set_boundary(alone.box_side(kMinusY), Boundary::Rigid);
  auto top = loads_on(m.face_groups.at("top_a"), 1.0), top_b = loads_on(m.face_groups.at("top_b"), 2.0);
  top.insert(top.end(), top_b.begin(), top_b.end());
  const auto alone_top_a = loads_on(alone.box_side(kPlusY), 1.0), alone_top_b = loads_on(alone.box_side(kPlusY), 2.0);
  for (RuleSet rules : {RuleSet::Patent, RuleSet::Conserving}) {
    const auto both = solved(body, rules, top);
    const auto a = solved(alone, rules, alone_top_a), b = solved(alone, rules, alone_top_b);
    for (int j = 0; j < 5; ++j)
      for (int i = 0; i < 10; ++i) {
        EXPECT_EQ(faces_at(both, {i, j, 0}), faces_at(a, {i, j, 0})) << i << "," << j;
        EXPECT_EQ(faces_at(both, {11 + i, j, 0}), faces_at(b, {i, j, 0})) << i << "," << j;
      }
    // 105 slots (not 5100) of 37 B, four scratch arrays of at most 21 doubles, and the touched-layer
    // list: 20 loads x 5 rows, 24 B each, in a vector of capacity at most 128.
    EXPECT_LE(both.memory_bytes(), 105u * 37u + 4u * 21u * 8u + 128u * 24u);
  }

  // The VTU's points are the nodes at their true places.
  agent_study::AgentStudy study;
  study.mesh = m;
  const auto vtu = agent_study::output_mesh(study);
  ASSERT_EQ(vtu.points.size(), 3u * 22u * 6u);
  EXPECT_NEAR(vtu.points[3 * g.node_index(11, 5, 0)], 1.010, 1e-12);
  EXPECT_NEAR(vtu.points[3 * g.node_index(11, 5, 0) + 1], 0.005, 1e-12);
}

TEST(CompressedLattice, AGapOfManyRowsAndColumnsGivesTheFaceForcesOfTheUncompressedBox) {
  // Part A: 6 x 4 agents at the origin; part B: 5 x 3 agents 50 columns right and 20 rows up;
  // part C: 4 x 3 agents in columns 30-33 beside A (A and C share rows: the directional rule
  // set's row balance spans both, at their true distance).
  // The uncompressed box (61 x 27 slots) against the compressed one (18 x 8): every agent's face
  // forces bit for bit, for each rule set, loads on the top of every part, bases rigid.
  const Eigen::Vector3d size(0.001, 0.001, 1);
  std::vector<std::array<std::int64_t, 3>> cells;
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 6; ++i) cells.push_back({i, j, 0});
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 5; ++i) cells.push_back({56 + i, 24 + j, 0});
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 4; ++i) cells.push_back({30 + i, j, 0});
  Grid wide = Grid::box(2, {61, 27, 1}, size);
  std::vector<std::int64_t> xs, ys;
  for (const auto& c : cells) xs.push_back(c[0]), ys.push_back(c[1]);
  const CompressedAxis ax(xs), ay(ys);
  Grid tight = Grid::lattice(2, {&ax, &ay, nullptr}, Eigen::Vector3d::Zero(), size);
  ASSERT_EQ(tight.cells, (std::array<int, 3>{17, 8, 1}));
  std::vector<char> wide_agent(wide.count(), 0), tight_agent(tight.count(), 0);
  for (const auto& c : cells) {
    wide_agent[wide.index(int(c[0]), int(c[1]), 0)] = 1;
    tight_agent[tight.index(int(ax.slot(c[0])), int(ay.slot(c[1])), 0)] = 1;
  }
  for (std::size_t s = 0; s < wide.count(); ++s)
    if (!wide_agent[s]) wide.make_air(s);
  for (std::size_t s = 0; s < tight.count(); ++s)
    if (!tight_agent[s]) tight.make_air(s);
  for (Grid* g : {&wide, &tight}) {
    std::vector<BoundaryFace> base;
    for (const auto& f : g->boundary_faces())
      if (f.side == kMinusY && (g->coords(f.cell)[1] == 0 || g->is_air(f.cell - g->stride(1)))) base.push_back(f);
    g->set_boundary(base, Boundary::Rigid);
  }
  // A load on the top of each part's columns, 1 N + 0.01 N per lattice column (an uneven load).
  std::vector<EntryLoad> wide_loads, tight_loads;
  for (const auto& c : cells)
    if ((c[1] == 3 && c[0] < 6) || c[1] == 26 || (c[1] == 2 && c[0] >= 30 && c[0] < 34)) {
      const double force = 1.0 + 0.01 * double(c[0]);
      wide_loads.push_back({wide.index(int(c[0]), int(c[1]), 0), direction(1, false), force});
      tight_loads.push_back({tight.index(int(ax.slot(c[0])), int(ay.slot(c[1])), 0), direction(1, false), force});
    }
  // Part B's agent (57, 25) is slot (13, 6): A's 6 columns, an air slot, C's 4, an air slot, then
  // 56, 57; 4 rows, an air slot, 24, 25.
  EXPECT_NEAR(tight.centre(tight.index(13, 6, 0))[0], wide.centre(wide.index(57, 25, 0))[0], 1e-15);
  EXPECT_NEAR(tight.centre(tight.index(13, 6, 0))[1], wide.centre(wide.index(57, 25, 0))[1], 1e-15);
  for (RuleSet rules : {RuleSet::Patent, RuleSet::Conserving, RuleSet::Directional}) {
    const auto a = solved(wide, rules, wide_loads), b = solved(tight, rules, tight_loads);
    for (const auto& c : cells)
      EXPECT_EQ(faces_at(a, {int(c[0]), int(c[1]), 0}), faces_at(b, {int(ax.slot(c[0])), int(ay.slot(c[1])), 0}))
          << int(rules) << ": " << c[0] << "," << c[1];
    EXPECT_EQ(a.diagnostics().rigid_reaction, b.diagnostics().rigid_reaction);
    EXPECT_LT(b.memory_bytes(), a.memory_bytes() / 8);
  }
}

TEST(CompressedLattice, AConnectedSparseStaircaseImportsOnTilesAndIsRefusedOnlyWhenTheyWouldNotFit) {
  // 2000 steps of two unit squares, face to face: (i, i) and (i + 1, i). No lattice plane is
  // empty, so the box is 2001 x 2000 slots (4.0e6, about 0.75 GiB at 200 B a slot) for 4000 agents;
  // on tiles it holds 188 tiles of 1024 slots (counted by hand in test_tiles.cc): 192512 slots,
  // 38.5 MB at 200 B a slot, plus the tile table (32 x 126 x 4 B) and three layers (3 x 2001 x 8 B).
  std::ostringstream msh;
  const int steps = 2000;
  msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << 4 * (steps + 1) << "\n";
  auto node = [](int i, int j) { return 1 + j * 4 + (i - j + 1); };  // nodes at y = j: x = j - 1 .. j + 2
  for (int j = 0; j <= steps; ++j)
    for (int d = 0; d < 4; ++d) msh << node(j - 1 + d, j) << " " << j - 1 + d << " " << j << " 0\n";
  msh << "$EndNodes\n$Elements\n" << 2 * steps << "\n";
  int tag = 1;
  for (int j = 0; j < steps; ++j)
    for (int i = j; i <= j + 1; ++i)  // the squares (j, j) and (j + 1, j): upper nodes in row j + 1 at x = i, i + 1
      msh << tag++ << " 3 2 1 1 " << node(i, j) << " " << node(i + 1, j) << " " << node(i + 1, j + 1) << " "
          << node(i, j + 1) << "\n";
  msh << "$EndElements\n";
  const auto file = test_support::write_file("staircase.msh", msh.str());
  auto import_with_limit = [&](const char* gib, std::string& error) {
    ::setenv("WORKBENCH_MEMORY_LIMIT", gib, 1);
    ImportedMesh m;
    try {
      m = import_mesh(file);
    } catch (const std::runtime_error& e) {
      error = e.what();
    }
    ::unsetenv("WORKBENCH_MEMORY_LIMIT");
    return m;
  };
  std::string error;
  const auto m = import_with_limit("0.1", error);
  ASSERT_EQ(error, "");
  EXPECT_TRUE(m.grid.tiled());
  EXPECT_EQ(m.grid.cells, (std::array<int, 3>{steps + 1, steps, 1}));
  EXPECT_EQ(m.grid.count(), 188u * 1024u);
  EXPECT_EQ(m.grid.agent_count(), 4000u);
  const double bytes = 192512.0 * 200 + 32 * 126 * 4 + 3 * 2001 * 8;
  std::vector<std::array<int, 3>> agents;
  for (std::size_t c : m.cell_of_element) agents.push_back(m.grid.coords(c));
  EXPECT_EQ(study_bytes(2, m.grid.cells, agents), bytes);
  // Each step's two agents are face neighbours, and the step above sits on the right one.
  for (int j = 0; j + 1 < steps; ++j) {
    const std::size_t left = m.grid.index(j, j, 0), right = m.grid.index(j + 1, j, 0);
    ASSERT_NE(left, Grid::npos);
    EXPECT_EQ(m.grid.neighbour(left, 1), right);
    EXPECT_EQ(m.grid.coords(m.grid.neighbour(right, 3)), (std::array<int, 3>{j + 1, j + 1, 0}));
    EXPECT_FALSE(m.grid.has_neighbour(left, 3));
  }
  import_with_limit("0.02", error);
  EXPECT_NE(error.find("4000 agents of 1 m in a compressed box of 2001 x 2000 slots"), std::string::npos) << error;
  EXPECT_NE(error.find("GiB, more than the 0.02 GiB allowed"), std::string::npos) << error;
}

TEST(CompressedLattice, VoxelizedDiscsFarApartAreTheirColumnsAndOneAirColumnAndReadBackIdentical) {
  // Discs of radius 1 at x = 0 and x = 1000, agents of 0.2: each disc spans 10 columns and 10
  // rows (the lattice starts at (-1, -1)); the gap of 4990 columns is one air slot: 21 x 10 slots.
  const auto msh = test_support::scratch_folder() / "two_discs.msh";
  const auto m = voxelize(kData + "two_discs.geo", 0.2, {}, msh);
  const Grid& g = m.grid;
  ASSERT_EQ(g.cells, (std::array<int, 3>{21, 10, 1}));
  EXPECT_EQ(g.planes[0].size(), 22u);
  EXPECT_TRUE(g.planes[1].empty());
  EXPECT_NEAR(g.plane(0, 10), 1.0, 1e-9);      // the first disc's right side
  EXPECT_NEAR(g.plane(0, 11), 999.0, 1e-9);    // the second disc's left side
  EXPECT_NEAR(g.plane(0, 21), 1001.0, 1e-9);
  for (int j = 0; j < 10; ++j) EXPECT_TRUE(g.is_air(g.index(10, j, 0)));
  // The same disc twice: as many agents left of the gap as right of it, each within the rim's
  // ring of pi r^2 / h^2 (test_mesh_import.cc, Voxelize.ADiscHasAboutPiRSquaredOverHSquaredAgents).
  std::size_t left = 0, right = 0;
  for (std::size_t c : m.cell_of_element) (g.coords(c)[0] < 10 ? left : right) += 1;
  EXPECT_EQ(left, right);
  EXPECT_NEAR(double(left), M_PI / 0.04, 2 * M_PI * std::sqrt(2.0) / 0.2);
  for (const auto& f : m.face_groups.at("rim")) {
    const Eigen::Vector3d c = g.centre(f.cell);
    const double r = (c - Eigen::Vector3d(c[0] < 500 ? 0.0 : 1000.0, 0, 0)).head<2>().norm();
    EXPECT_LT(std::abs(r - 1.0), 1.5 * 0.2) << f.cell;
  }
  // The staircase .msh holds the nodes at their true places: read back, it is the same grid.
  const auto back = import_mesh(msh);
  EXPECT_EQ(back.grid.cells, g.cells);
  EXPECT_EQ(back.grid.flags, g.flags);
  EXPECT_EQ(back.face_groups.at("rim").size(), m.face_groups.at("rim").size());
  for (std::size_t c : m.cell_of_element) EXPECT_LT((back.grid.centre(c) - g.centre(c)).norm(), 1e-9) << c;
}

TEST(CompressedLattice, TwoCubesFarApartIn3DAreThreeByOneByThreeSlots) {
  // Unit cubes at (0, 0, 0) and (1e6, 0, 1e6) (MSH 2.2 hexahedra): x and z compress to cube, air,
  // cube; the cube on the far side solves as it does alone, in each rule set.
  std::ostringstream msh;
  msh.precision(17);
  msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n16\n";
  const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
  for (int cube = 0; cube < 2; ++cube)
    for (int k = 0; k < 8; ++k)
      msh << 8 * cube + k + 1 << " " << corner[k][0] + 1e6 * cube << " " << corner[k][1] << " " << corner[k][2] + 1e6 * cube << "\n";
  msh << "$EndNodes\n$Elements\n2\n";
  for (int cube = 0; cube < 2; ++cube) {
    msh << cube + 1 << " 5 2 1 1";
    for (int k = 0; k < 8; ++k) msh << " " << 8 * cube + k + 1;
    msh << "\n";
  }
  msh << "$EndElements\n";
  const auto m = import_mesh(test_support::write_file("two_cubes.msh", msh.str()));
  const Grid& g = m.grid;
  ASSERT_EQ(g.cells, (std::array<int, 3>{3, 1, 3}));
  EXPECT_EQ(g.agent_count(), 2u);
  EXPECT_EQ(g.centre(g.index(2, 0, 2)), Eigen::Vector3d(1e6 + 0.5, 0.5, 1e6 + 0.5));
  EXPECT_EQ(g.node_position(3, 1, 3), Eigen::Vector3d(1e6 + 1, 1, 1e6 + 1));
  Grid body = g, alone = Grid::box(3, {1, 1, 1}, Eigen::Vector3d(1, 1, 1));
  body.set_boundary({{g.index(2, 0, 2), kMinusY}}, Boundary::Rigid);
  alone.set_boundary({{0, kMinusY}}, Boundary::Rigid);
  for (RuleSet rules : {RuleSet::Patent, RuleSet::Conserving, RuleSet::Directional}) {
    const auto both = solved(body, rules, {{g.index(2, 0, 2), direction(1, false), 4.0}});
    EXPECT_EQ(faces_at(both, {2, 0, 2}), faces_at(solved(alone, rules, {{0, direction(1, false), 4.0}}), {0, 0, 0}));
    EXPECT_DOUBLE_EQ(both.diagnostics().rigid_reaction + both.diagnostics().passed_out + both.diagnostics().dropped +
                         both.diagnostics().lost, 4.0);
  }
}
