// The comparison's consumers of the agent grid on a tiled grid (agent::Tiles): the FEM sampled
// onto the agents, the probe points, the near-load mask, line sampling and the output mesh give
// bit for bit what they give on the dense grid of the same body; so do a sparse staircase .msh's,
// which imports on tiles, beside the same body laid out densely.
#include <agent/mesh_import.h>
#include <agent_study.h>
#include <fem_reference/fem_case.h>
#include <workbench/case_file.h>
#include <compare/metrics.h>
#include <compare/reference.h>

#include "../support/agent_fixtures.h"
#include "../support/scratch_folder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

using namespace compare;

namespace {

/// The same imported body on tiles: the grid by agent::tile, elements and face groups renumbered.
agent::ImportedMesh tiled_copy(const agent::ImportedMesh& dense) {
  agent::ImportedMesh t = dense;
  t.grid = agent::tile(dense.grid);
  auto id = [&](std::size_t cell) {
    const auto c = dense.grid.coords(cell);
    return t.grid.index(c[0], c[1], c[2]);
  };
  for (auto& cell : t.cell_of_element) cell = id(cell);
  for (auto& [name, faces] : t.face_groups)
    for (auto& f : faces) f.cell = id(f.cell);
  return t;
}

fem_reference::FemProblem plate_problem() {
  fem_reference::FemProblem p;
  p.name = "plate";
  p.mesh_file = WORKBENCH_SOURCE_DIR "/meshes/plate2d.geo";
  p.mesh_parameters = {{"W", 0.04}, {"H", 0.02}, {"h", 0.002}, {"lw", 0.008}};
  p.thickness = 0.002;
  p.supports.push_back({"base", fem_reference::SupportKind::Clamped, {}});
  fem_reference::Traction load;
  load.group = "load";
  load.force = {0, -2.0, 0};
  p.tractions.push_back(load);
  p.options.write_vtu = false;
  return p;
}

agent::ImportedMesh plate_mesh() {
  const auto p = plate_problem();
  return agent::import_mesh(p.mesh_file, p.mesh_parameters);
}

}  // namespace

TEST(TiledCompare, FemOnGridProbesAndNearLoadEqualTheDenseGrids) {
  const auto dense = plate_mesh();
  const auto tiled = tiled_copy(dense);
  ASSERT_FALSE(dense.grid.tiled());
  ASSERT_TRUE(tiled.grid.tiled());
  const auto& d = dense.grid;
  const auto& t = tiled.grid;

  // The body's nodes, listed in box order on both layouts: the same positions, in the same order.
  const auto dn = body_node_ids(d), tn = body_node_ids(t);
  ASSERT_EQ(dn.size(), tn.size());
  ASSERT_EQ(dn.size(), std::size_t((d.cells[0] + 1) * (d.cells[1] + 1)));  // a full rectangle of agents
  for (std::size_t n = 0; n < dn.size(); ++n) EXPECT_EQ(d.node_coords(dn[n]), t.node_coords(tn[n])) << n;
  EXPECT_EQ(agent_probe_points(d), agent_probe_points(t));

  const auto fem = fem_reference::solve_fem(plate_problem());
  const auto fd = fem_on_grid(dense, fem, "plate"), ft = fem_on_grid(tiled, fem, "plate");
  EXPECT_EQ(test_support::in_dense_order(d, t, ft.stress, kStressSlots, 0.0), fd.stress);
  EXPECT_EQ(test_support::in_dense_order(d, t, ft.u, 2, 0.0, true), fd.u);
  // FEM evaluated at the probe points (as on a true geometry's mesh): the same fields again.
  auto probed = plate_problem();
  probed.probe_points = agent_probe_points(d);
  const auto fem_probed = fem_reference::solve_fem(probed);
  std::array<std::size_t, 2> outside_d{}, outside_t{};
  const auto pd = fem_at_agents(d, fem_probed, outside_d), pt = fem_at_agents(t, fem_probed, outside_t);
  EXPECT_EQ(test_support::in_dense_order(d, t, pt.stress, kStressSlots, 0.0), pd.stress);
  EXPECT_EQ(test_support::in_dense_order(d, t, pt.u, 2, 0.0, true), pd.u);
  EXPECT_EQ(outside_d, outside_t);
  for (std::size_t n : dn)  // the plate's own mesh: every probe found, the nodal values FEM's
    for (int c = 0; c < 2; ++c) EXPECT_NEAR(pd.u[2 * n + c], fd.u[2 * n + c], 1e-9 * std::abs(fd.u[2 * n + 1]) + 1e-18);
  double largest = 0;
  for (double s : fd.stress) largest = std::max(largest, std::abs(s));
  EXPECT_GT(largest, 10.0);  // 2 N on 8 mm x 2 mm: about 125 kPa under the load

  workbench::LoadSpec load;
  load.group = "load";
  load.axis = 1;
  load.sign = -1;
  const std::vector<workbench::LoadSpec> loads{load};
  const auto nd = near_load(dense, loads, 0.005), nt = near_load(tiled, loads, 0.005);
  const auto cells_d = test_support::in_dense_order(d, t, nt.cells, 1, char(2));
  for (std::size_t c = 0; c < d.count(); ++c) EXPECT_EQ(cells_d[c], nd.cells[c]) << c;
  EXPECT_EQ(test_support::in_dense_order(d, t, nt.nodes, 1, char(2), true), nd.nodes);
  EXPECT_GT(std::count(nd.nodes.begin(), nd.nodes.end(), 1), 0);
  EXPECT_GT(std::count(nd.nodes.begin(), nd.nodes.end(), 0), 0);

  // Sample lines along and across the load: every sample of both fields the same number.
  const auto lines_d = load_lines(d, load_frames(dense, loads), {0.25, 0.5});
  const auto lines_t = load_lines(t, load_frames(tiled, loads), {0.25, 0.5});
  ASSERT_EQ(lines_d.size(), lines_t.size());
  for (std::size_t l = 0; l < lines_d.size(); ++l) {
    ASSERT_EQ(lines_d[l].body_samples, lines_t[l].body_samples);
    for (int i = 0; i < lines_d[l].samples; ++i) {
      const auto p = lines_d[l].point(i);
      for (int c = 0; c < 2; ++c) {
        EXPECT_EQ(sample_cells(d, fd.stress, kStressSlots, c, p), sample_cells(t, ft.stress, kStressSlots, c, p));
        EXPECT_EQ(sample_nodes(d, fd.u, 2, c, p), sample_nodes(t, ft.u, 2, c, p));
      }
    }
  }
}

TEST(TiledCompare, SamplingBesideAirAndUnstoredTilesEqualsTheDenseGrid) {
  // A 200 x 40 box with agents in its bottom row and left column only: most tiles hold no agent,
  // so points in them sample unstored slots and nodes (air: cell weights renormalised, node 0).
  auto d = agent::Grid::box(2, {200, 40, 1}, Eigen::Vector3d(1e-3, 1e-3, 1));
  for (std::size_t c = 0; c < d.count(); ++c) {
    const auto x = d.coords(c);
    if (x[0] > 0 && x[1] > 0) d.make_air(c);
  }
  const auto t = agent::tile(d);
  ASSERT_TRUE(t.tiled());
  ASSERT_LT(t.count(), d.count());
  std::vector<double> cells(2 * d.count(), 0.0), nodes(2 * d.node_count(), 0.0);
  const auto body = body_nodes(d);
  for (std::size_t c = 0; c < d.count(); ++c)
    if (!d.is_air(c)) cells[2 * c] = 1 + double(c), cells[2 * c + 1] = -double(c);
  for (std::size_t n = 0; n < d.node_count(); ++n)
    if (body[n]) nodes[2 * n] = 0.5 + double(n), nodes[2 * n + 1] = 2.0 * double(n);
  // The tiled grid's fields: the dense values at the same box coordinates, 0 elsewhere.
  std::vector<double> tcells(2 * t.count(), 0.0), tnodes(2 * t.node_count(), 0.0);
  for (std::size_t c = 0; c < d.count(); ++c) {
    const auto x = d.coords(c);
    const std::size_t at = t.index(x[0], x[1], x[2]);
    if (at != agent::Grid::npos) tcells[2 * at] = cells[2 * c], tcells[2 * at + 1] = cells[2 * c + 1];
  }
  for (std::size_t n = 0; n < d.node_count(); ++n) {
    const auto x = d.node_coords(n);
    const std::size_t at = t.node_index(x[0], x[1], x[2]);
    if (at != agent::Grid::npos) tnodes[2 * at] = nodes[2 * n], tnodes[2 * at + 1] = nodes[2 * n + 1];
  }
  int in_body = 0, nan_cells = 0;
  for (double x = -0.3e-3; x < 200.3e-3; x += 0.77e-3)
    for (double y = -0.3e-3; y < 40.3e-3; y += 0.41e-3) {
      const Eigen::Vector3d p(x, y, 0);
      EXPECT_EQ(compare::in_body(d, p), compare::in_body(t, p));
      in_body += compare::in_body(t, p);
      for (int c = 0; c < 2; ++c) {
        const double a = sample_cells(d, cells, 2, c, p), b = sample_cells(t, tcells, 2, c, p);
        if (std::isnan(a)) {
          EXPECT_TRUE(std::isnan(b));
          nan_cells += c == 0;
        } else {
          EXPECT_EQ(a, b) << x << "," << y;
        }
        EXPECT_EQ(sample_nodes(d, nodes, 2, c, p), sample_nodes(t, tnodes, 2, c, p)) << x << "," << y;
      }
    }
  EXPECT_GT(in_body, 0);
  EXPECT_GT(nan_cells, 0);  // far from every agent: no value
}

TEST(TiledCompare, OutputMeshPutsEveryAgentsCornersWhereTheDenseMeshDoes) {
  agent_study::AgentStudy dense;
  dense.mesh = plate_mesh();
  agent_study::AgentStudy tiled = dense;
  tiled.mesh = tiled_copy(dense.mesh);
  const auto md = agent_study::output_mesh(dense), mt = agent_study::output_mesh(tiled);
  EXPECT_EQ(md.points.size(), 3 * dense.mesh.grid.node_count());
  EXPECT_EQ(mt.points.size(), 3 * tiled.mesh.grid.node_count());
  ASSERT_EQ(md.connectivity.size(), mt.connectivity.size());
  for (std::size_t v = 0; v < md.connectivity.size(); ++v)
    for (int a = 0; a < 3; ++a)
      EXPECT_EQ(md.points[3 * std::size_t(md.connectivity[v]) + a], mt.points[3 * std::size_t(mt.connectivity[v]) + a]) << v;
}

namespace {

/// The same imported body on a dense grid (a test may hold the box: 301 x 300 slots here).
agent::ImportedMesh dense_copy(const agent::ImportedMesh& tiled) {
  const auto& t = tiled.grid;
  agent::ImportedMesh d = tiled;
  d.grid = agent::Grid::box(t.dim, t.cells, t.size, t.thickness);
  d.grid.origin = t.origin;
  d.grid.planes = t.planes;
  for (std::size_t c = 0; c < d.grid.count(); ++c) {
    const auto x = d.grid.coords(c);
    const std::size_t at = t.index(x[0], x[1], x[2]);
    d.grid.flags[c] = at == agent::Grid::npos ? agent::Grid::kAirBit : t.flags[at];
  }
  auto id = [&](std::size_t cell) {
    const auto x = t.coords(cell);
    return d.grid.index(x[0], x[1], x[2]);
  };
  for (auto& cell : d.cell_of_element) cell = id(cell);
  for (auto& [name, faces] : d.face_groups)
    for (auto& f : faces) f.cell = id(f.cell);
  return d;
}

}  // namespace

namespace {

const int kSteps = 300;

/// Writes the staircase and its case file into the test's scratch folder: kSteps steps of two 1 mm
/// squares, face to face: (i, i) and (i + 1, i), a 301 x 300 box whose stored tiles hold a tenth
/// of it. Clamped under the bottom step ("base"), pushed down on the top one ("load").
std::filesystem::path staircase_case() {
  const int steps = kSteps;
  std::ostringstream msh;
  msh << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n1 1 \"base\"\n1 2 \"load\"\n2 3 \"body\"\n"
      << "$EndPhysicalNames\n$Nodes\n" << 4 * (steps + 1) << "\n";
  auto node = [](int i, int j) { return 1 + j * 4 + (i - j + 1); };  // nodes at y = j: x = j - 1 .. j + 2
  for (int j = 0; j <= steps; ++j)
    for (int d = 0; d < 4; ++d) msh << node(j - 1 + d, j) << " " << 1e-3 * (j - 1 + d) << " " << 1e-3 * j << " 0\n";
  msh << "$EndNodes\n$Elements\n" << 2 * steps + 4 << "\n";
  int tag = 1;
  for (int i = 0; i <= 1; ++i) msh << tag++ << " 1 2 1 1 " << node(i, 0) << " " << node(i + 1, 0) << "\n";
  for (int i = steps; i <= steps + 1; ++i)
    msh << tag++ << " 1 2 2 2 " << node(i, steps) << " " << node(i - 1, steps) << "\n";
  for (int j = 0; j < steps; ++j)
    for (int i = j; i <= j + 1; ++i)
      msh << tag++ << " 3 2 3 3 " << node(i, j) << " " << node(i + 1, j) << " " << node(i + 1, j + 1) << " "
          << node(i, j + 1) << "\n";
  msh << "$EndElements\n";
  test_support::write_file("staircase.msh", msh.str());
  return test_support::write_file("staircase.toml", R"(title = "staircase on tiles"
[mesh]
file = "staircase.msh"
[material]
young = 1e9
poisson = 0.3
thickness = 0.001
[boundary]
rigid = ["base"]
[[load]]
group = "load"
direction = "-y"
force = 1.0
[agent]
rule_set = "conserving"
[fem]
degree = 1
[compare]
figures = false
[compare.reference]
degree = 1
refine = 0
)");
}

}  // namespace

TEST(TiledCompare, AnImportedSparseStaircaseIsSampledAsOnADenseGrid) {
  // No agent model here: the FEM on the staircase, its probe points, the near-load mask and the
  // sample lines, on the imported tiled grid and on the same body laid out densely.
  const workbench::CaseFile file(staircase_case());
  const auto tiled = agent_study::load_agent_study(file);
  const auto& t = tiled.mesh.grid;
  ASSERT_TRUE(t.tiled());
  ASSERT_EQ(t.agent_count(), std::size_t(2 * kSteps));
  ASSERT_LT(t.count(), std::size_t(t.cells[0]) * t.cells[1] / 2);
  const auto dense = dense_copy(tiled.mesh);
  const auto& d = dense.grid;
  ASSERT_EQ(d.agent_count(), t.agent_count());

  // The agents and the body's nodes in box order on both layouts (the order sums over the body add in).
  const auto ad = agent_ids(d), at = agent_ids(t), nd_ids = body_node_ids(d), nt_ids = body_node_ids(t);
  ASSERT_EQ(ad.size(), std::size_t(2 * kSteps));
  ASSERT_EQ(at.size(), ad.size());
  for (std::size_t a = 0; a < ad.size(); ++a) EXPECT_EQ(t.coords(at[a]), d.coords(ad[a])) << a;
  ASSERT_EQ(nt_ids.size(), nd_ids.size());
  for (std::size_t n = 0; n < nd_ids.size(); ++n) EXPECT_EQ(t.node_coords(nt_ids[n]), d.node_coords(nd_ids[n])) << n;
  EXPECT_EQ(agent_probe_points(d), agent_probe_points(t));
  EXPECT_EQ(agent_probe_points(t).size(), std::size_t(4 * 2 * kSteps + 4 * kSteps + 2));  // Gauss points, body nodes
  auto problem = fem_reference::problem_from_case(file);
  problem.options.write_vtu = false;
  const auto fem = fem_reference::solve_fem(problem);
  const auto fd = fem_on_grid(dense, fem, "staircase"), ft = fem_on_grid(tiled.mesh, fem, "staircase");
  EXPECT_EQ(test_support::in_dense_order(d, t, ft.stress, kStressSlots, 0.0), fd.stress);
  EXPECT_EQ(test_support::in_dense_order(d, t, ft.u, 2, 0.0, true), fd.u);
  // Equilibrium of the top step: its two agents carry the load, 1 N over 2 mm x 1 mm, on average.
  const std::size_t top[2] = {d.index(kSteps - 1, kSteps - 1, 0), d.index(kSteps, kSteps - 1, 0)};
  EXPECT_NEAR(0.5 * (fd.stress[kStressSlots * top[0] + kSigmaY] + fd.stress[kStressSlots * top[1] + kSigmaY]), -1.0 / (2e-3 * 1e-3), 0.3 / (2e-3 * 1e-3));

  const auto nd = near_load(dense, tiled.setup.loads, 0.005), nt = near_load(tiled.mesh, tiled.setup.loads, 0.005);
  const auto near_cells = test_support::in_dense_order(d, t, nt.cells, 1, char(2));
  const auto near_nodes = test_support::in_dense_order(d, t, nt.nodes, 1, char(2), true);
  std::size_t near_agents = 0;
  for (std::size_t c : dense.cell_of_element) {
    EXPECT_EQ(near_cells[c], nd.cells[c]) << c;
    near_agents += nd.cells[c];
  }
  for (std::size_t n : body_node_ids(d)) EXPECT_EQ(near_nodes[n], nd.nodes[n]) << n;
  EXPECT_GT(near_agents, 0u);  // the top steps within 5 mm of the loaded face, not the whole stair
  EXPECT_LT(near_agents, std::size_t(2 * kSteps));

  const auto lines_d = load_lines(d, load_frames(dense, tiled.setup.loads), {0.25, 0.5});
  const auto lines_t = load_lines(t, load_frames(tiled.mesh, tiled.setup.loads), {0.25, 0.5});
  ASSERT_EQ(lines_d.size(), lines_t.size());
  std::size_t in_body = 0;
  for (std::size_t l = 0; l < lines_d.size(); ++l) {
    ASSERT_EQ(lines_d[l].body_samples, lines_t[l].body_samples);
    in_body += lines_t[l].body_samples.size();
    for (int i = 0; i < lines_d[l].samples; ++i) {
      const auto p = lines_d[l].point(i);
      for (int c = 0; c < 2; ++c) {
        const double a = sample_cells(d, fd.stress, kStressSlots, c, p), b = sample_cells(t, ft.stress, kStressSlots, c, p);
        EXPECT_TRUE(a == b || (std::isnan(a) && std::isnan(b))) << l << " " << i;
        EXPECT_EQ(sample_nodes(d, fd.u, 2, c, p), sample_nodes(t, ft.u, 2, c, p)) << l << " " << i;
      }
    }
  }
  EXPECT_GT(in_body, 0u);
}
