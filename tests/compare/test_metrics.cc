// Sampling and error norms of the comparison, against closed forms.
#include <compare/metrics.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace compare;

namespace {
agent::Grid grid2d() { return agent::Grid::box(2, {8, 5, 1}, Eigen::Vector3d(0.5, 0.25, 1)); }
}  // namespace

TEST(CompareSampling, BilinearFieldsAreSampledExactly) {
  const auto g = grid2d();
  auto f = [](double x, double y) { return 3.0 + 2.0 * x - 5.0 * y + 0.5 * x * y; };
  std::vector<double> cells(g.count()), nodes(g.node_count());
  for (std::size_t c = 0; c < g.count(); ++c) cells[c] = f(g.centre(c)[0], g.centre(c)[1]);
  for (int j = 0; j <= 5; ++j)
    for (int i = 0; i <= 8; ++i) nodes[g.node_index(i, j, 0)] = f(0.5 * i, 0.25 * j);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.3, 0.2, 0), Eigen::Vector3d(2.1, 0.9, 0), Eigen::Vector3d(3.75, 1.125, 0)}) {
    EXPECT_NEAR(sample_nodes(g, nodes, 1, 0, p), f(p[0], p[1]), 1e-12);
    // Between the outer cell centres the cell field is bilinear too.
    if (p[0] >= 0.25 && p[0] <= 3.75 && p[1] >= 0.125 && p[1] <= 1.125) {
      EXPECT_NEAR(sample_cells(g, cells, 1, 0, p), f(p[0], p[1]), 1e-12);
    }
  }
  // Past the outer centres the cell field is held constant.
  EXPECT_NEAR(sample_cells(g, cells, 1, 0, Eigen::Vector3d(0.0, 0.125, 0)), f(0.25, 0.125), 1e-12);
}

namespace {
/// The 8 x 5 grid with face groups: "a" and "b" on top of columns 1 and 6, "s" on the left of row 2.
agent::ImportedMesh mesh2d() {
  agent::ImportedMesh m;
  m.grid = grid2d();
  m.face_groups["a"] = {{m.grid.index(1, 4, 0), agent::direction(1, true)}};
  m.face_groups["b"] = {{m.grid.index(6, 4, 0), agent::direction(1, true)}};
  m.face_groups["s"] = {{m.grid.index(0, 2, 0), agent::direction(0, false)}};
  for (std::size_t c = 0; c < m.grid.count(); ++c) m.cell_of_element.push_back(c);
  return m;
}
workbench::LoadSpec load(const std::string& group, int axis, int sign) {
  workbench::LoadSpec l;
  l.group = group;
  l.axis = axis;
  l.sign = sign;
  l.force = 1.0;
  return l;
}
}  // namespace

TEST(CompareLines, TwoLoadsGetALineEachThroughTheirOwnPatch) {
  const auto m = mesh2d();
  const auto frames = load_frames(m, {load("a", 1, -1), load("b", 1, -1)});
  ASSERT_EQ(frames.size(), 2u);
  EXPECT_DOUBLE_EQ(frames[0].centre[0], 0.75);
  EXPECT_DOUBLE_EQ(frames[1].centre[0], 3.25);
  EXPECT_DOUBLE_EQ(frames[0].centre[1], 1.25);
  const auto lines = load_lines(m.grid, frames, {0.5});
  // Each load's own vertical line; the line across at half depth is the same for both: once.
  ASSERT_EQ(lines.size(), 3u);
  for (int k : {0, 2}) {
    const double x = k == 0 ? 0.75 : 3.25;
    EXPECT_DOUBLE_EQ(lines[k].from[0], x);
    EXPECT_DOUBLE_EQ(lines[k].to[0], x);
    EXPECT_DOUBLE_EQ(lines[k].from[1], 1.125);  // the first agent centre under the patch
    EXPECT_DOUBLE_EQ(lines[k].to[1], 0.125);
    EXPECT_EQ(lines[k].samples, 5);
  }
  EXPECT_EQ(lines[0].name, "line_x750y1125_x750y125");
  EXPECT_EQ(lines[2].name, "line_x3250y1125_x3250y125");
  EXPECT_DOUBLE_EQ(lines[1].from[1], 0.625);
  EXPECT_DOUBLE_EQ(lines[1].to[1], 0.625);
  EXPECT_DOUBLE_EQ(lines[1].from[0], 0.25);
  EXPECT_DOUBLE_EQ(lines[1].to[0], 3.75);
  EXPECT_EQ(lines[1].samples, 8);
}

TEST(CompareLines, ASideLoadsLinesAreTurned) {
  const auto m = mesh2d();
  const auto lines = load_lines(m.grid, load_frames(m, {load("s", 0, +1)}), {0.25});
  ASSERT_EQ(lines.size(), 2u);
  // Along the load (+x) at the patch's height, from the loaded left side across the body.
  EXPECT_DOUBLE_EQ(lines[0].from[1], 0.625);
  EXPECT_DOUBLE_EQ(lines[0].to[1], 0.625);
  EXPECT_DOUBLE_EQ(lines[0].from[0], 0.25);
  EXPECT_DOUBLE_EQ(lines[0].to[0], 3.75);
  // Across it (along y) at a quarter of the width in from the loaded side.
  EXPECT_DOUBLE_EQ(lines[1].from[0], 1.0);
  EXPECT_DOUBLE_EQ(lines[1].to[0], 1.0);
  EXPECT_DOUBLE_EQ(lines[1].from[1], 0.125);
  EXPECT_DOUBLE_EQ(lines[1].to[1], 1.125);
}

TEST(CompareLines, OneNameFromTheCoordinates) {
  // depths = [0.1234] on a 200 mm plate: the line at y = 175.32 mm has one name everywhere.
  EXPECT_EQ(line_name(Eigen::Vector3d(0.1, 0.17532, 0), Eigen::Vector3d(0, -0.0015, 0), 2), "line_x100y175p32_x0ym1p5");
  EXPECT_EQ(line_name(Eigen::Vector3d(0, 0, 0.002), Eigen::Vector3d(0.001, 0, 0), 3), "line_x0y0z2_x1y0z0");
}

TEST(CompareFarField, TheMaskLeavesOutExactlyTheCellsAndNodesWithinTheDistance) {
  const auto m = mesh2d();
  // Patch "a": x in [0.5, 1], y = 1.25. Within 0.3 of it: the centres (0.25 | 0.75 | 1.25, 1.125)
  // (distances 0.2795, 0.125, 0.2795); the next ones are 0.375 (below) and 0.76 (beside) away.
  const auto near = near_load(m, {load("a", 1, -1)}, 0.3);
  std::vector<std::size_t> cells, nodes;
  for (std::size_t c = 0; c < near.cells.size(); ++c)
    if (near.cells[c]) cells.push_back(c);
  for (std::size_t n = 0; n < near.nodes.size(); ++n)
    if (near.nodes[n]) nodes.push_back(n);
  EXPECT_EQ(cells, (std::vector<std::size_t>{m.grid.index(0, 4, 0), m.grid.index(1, 4, 0), m.grid.index(2, 4, 0)}));
  // Nodes x = 0.5, 1 at y = 1 (0.25 away) and y = 1.25 (on the patch); x = 0 and 1.5 are 0.5 away.
  EXPECT_EQ(nodes, (std::vector<std::size_t>{m.grid.node_index(1, 4, 0), m.grid.node_index(2, 4, 0),
                                             m.grid.node_index(1, 5, 0), m.grid.node_index(2, 5, 0)}));
}

TEST(CompareNorms, RelativeErrorsAndMaskedRatios) {
  const std::vector<double> ref{1.0, -2.0, 2.0, 0.001}, model{1.5, -2.0, 1.0, 0.003};
  const auto e = relative_errors(model, ref);
  EXPECT_NEAR(e.rel_l2, std::sqrt(0.25 + 1.0 + 0.002 * 0.002) / std::sqrt(1 + 4 + 4 + 1e-6), 1e-15);
  EXPECT_DOUBLE_EQ(e.rel_max, 0.5);
  const auto r = ratios(model, ref, 0.01);
  EXPECT_EQ(r.masked_count, 1u);  // |0.001| < 0.01 * 2
  EXPECT_EQ(r.masked[3], 1);
  EXPECT_DOUBLE_EQ(r.ratio[0], 1.5);
  EXPECT_DOUBLE_EQ(r.ratio[2], 0.5);
  EXPECT_DOUBLE_EQ(r.median, 1.0);  // of 1.5, 1, 0.5
  // mask 0: every nonzero reference gives a ratio, a zero one is masked (no x / 0 in cells.csv).
  const auto r0 = ratios({2.0, 1.0, 0.0}, {4.0, 0.0, 0.0}, 0.0);
  EXPECT_EQ(r0.masked_count, 2u);
  EXPECT_EQ(r0.masked[0], 0);
  EXPECT_DOUBLE_EQ(r0.ratio[0], 0.5);
  EXPECT_EQ(r0.ratio[1], 0.0);
  EXPECT_EQ(relative_errors({0, 0}, {0, 0}).rel_l2, 0.0);
  EXPECT_TRUE(std::isinf(relative_errors({1, 0}, {0, 0}).rel_l2));
}

// Air slots hold no value. A cell field sampled next to air is the bilinear weights of the
// agents only, renormalised; a line stops at air.
TEST(CompareAir, SamplingNextToAirUsesTheAgentsOnlyWithRenormalisedWeights) {
  auto g = grid2d();  // 8 x 5 agents of 0.5 x 0.25; the slots i >= 5, j >= 3 are air (a notch)
  for (int j = 3; j < 5; ++j)
    for (int i = 5; i < 8; ++i) g.make_air(g.index(i, j, 0));
  std::vector<double> cells(g.count());
  for (std::size_t c = 0; c < g.count(); ++c) cells[c] = g.is_air(c) ? 1e9 : double(c);  // air: a value that must not show
  // (2.4, 0.7): t = 0.3 along x between centres 2.25 and 2.75, 0.3 along y between 0.625 and 0.875;
  // the stencil (4,2) (5,2) (4,3) (5,3) has weights 0.49, 0.21, 0.21 and 0.09 on the air slot (5,3).
  const Eigen::Vector3d p(2.4, 0.7, 0);
  EXPECT_TRUE(in_body(g, p));
  EXPECT_NEAR(sample_cells(g, cells, 1, 0, p), (0.49 * 20 + 0.21 * 21 + 0.21 * 28) / 0.91, 1e-12);
  // Away from air the weights are the plain bilinear ones.
  EXPECT_NEAR(sample_cells(g, cells, 1, 0, Eigen::Vector3d(1.4, 0.7, 0)), 0.49 * 18 + 0.21 * 19 + 0.21 * 26 + 0.09 * 27,
              1e-12);
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(2.5, 0.75, 0)));   // the notch's corner slot (5,3)
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(3.9, 1.2, 0)));    // deep in the notch
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(4.1, 0.5, 0)));    // outside the box
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(-0.1, 0.5, 0)));
  EXPECT_TRUE(std::isnan(sample_cells(g, cells, 1, 0, Eigen::Vector3d(3.9, 1.2, 0))));  // no agent around it
}

TEST(CompareAir, ALineAcrossAHoleStopsAtItsRim) {
  auto g = agent::Grid::box(2, {10, 5, 1}, Eigen::Vector3d(1, 1, 1));
  for (int j = 1; j <= 3; ++j)
    for (int i = 4; i <= 5; ++i) g.make_air(g.index(i, j, 0));  // a 2 x 3 hole
  const auto l = make_line(g, Eigen::Vector3d(0.5, 2.5, 0), Eigen::Vector3d(9.5, 2.5, 0), "across", "user");
  EXPECT_EQ(l.samples, 10);
  EXPECT_EQ(l.body_samples, (std::vector<int>{0, 1, 2, 3, 6, 7, 8, 9}));
  // Below the hole the same line runs through.
  EXPECT_EQ(make_line(g, Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(9.5, 0.5, 0), "below", "user").body_samples.size(), 10u);
}

TEST(CompareSampling, ACompressedGridIsSampledAndCrossedByLinesAtTrueCoordinates) {
  // Two 4 x 2 parts of unit agents, columns 0-3 and 1000-1003: 9 x 2 slots (slot 4 the gap).
  const agent::CompressedAxis ax({0, 1, 2, 3, 1000, 1001, 1002, 1003}), ay({0, 1});
  agent::Grid g = agent::Grid::lattice(2, {&ax, &ay, nullptr}, Eigen::Vector3d::Zero(), Eigen::Vector3d(1, 1, 1));
  ASSERT_EQ(g.cells, (std::array<int, 3>{9, 2, 1}));
  for (int j = 0; j < 2; ++j) g.make_air(g.index(4, j, 0));
  EXPECT_TRUE(in_body(g, Eigen::Vector3d(1001.2, 0.5, 0)));
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(500, 0.5, 0)));
  EXPECT_FALSE(in_body(g, Eigen::Vector3d(4.5, 0.5, 0)));  // the first column of the gap
  // A cell field equal to x and a node field equal to x + y are sampled exactly in each part.
  std::vector<double> cells(g.count()), nodes(g.node_count());
  for (std::size_t c = 0; c < g.count(); ++c) cells[c] = g.centre(c)[0];
  for (int j = 0; j <= 2; ++j)
    for (int i = 0; i <= 9; ++i) nodes[g.node_index(i, j, 0)] = g.node_position(i, j, 0)[0] + j;
  EXPECT_DOUBLE_EQ(sample_cells(g, cells, 1, 0, Eigen::Vector3d(1001.5, 0.5, 0)), 1001.5);
  EXPECT_DOUBLE_EQ(sample_cells(g, cells, 1, 0, Eigen::Vector3d(1001.75, 1.5, 0)), 1001.75);
  EXPECT_DOUBLE_EQ(sample_nodes(g, nodes, 1, 0, Eigen::Vector3d(1002.25, 0.5, 0)), 1002.75);
  // A line across both parts: one sample per slot (8 agents and the gap), the gap's sample in air.
  const auto l = make_line(g, Eigen::Vector3d(0.5, 0.5, 0), Eigen::Vector3d(1003.5, 0.5, 0), "across", "user");
  ASSERT_EQ(l.samples, 9);
  EXPECT_EQ(l.body_samples, (std::vector<int>{0, 1, 2, 3, 5, 6, 7, 8}));
  EXPECT_DOUBLE_EQ(l.point(3)[0], 3.5);
  EXPECT_DOUBLE_EQ(l.point(4)[0], 502.0);  // the middle of the gap [4, 1000]
  EXPECT_DOUBLE_EQ(l.point(5)[0], 1000.5);
  EXPECT_DOUBLE_EQ(l.point(8)[0], 1003.5);
}
