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
  for (const Eigen::Vector3d p : {Eigen::Vector3d(0.3, 0.2, 0), Eigen::Vector3d(2.1, 0.9, 0), Eigen::Vector3d(3.75, 1.125, 0)}) {
    EXPECT_NEAR(sample_nodes(g, nodes, 1, 0, p), f(p[0], p[1]), 1e-12);
    // Between the outer cell centres the cell field is bilinear too.
    if (p[0] >= 0.25 && p[0] <= 3.75 && p[1] >= 0.125 && p[1] <= 1.125)
      EXPECT_NEAR(sample_cells(g, cells, 1, 0, p), f(p[0], p[1]), 1e-12);
  }
  // Past the outer centres the cell field is held constant.
  EXPECT_NEAR(sample_cells(g, cells, 1, 0, Eigen::Vector3d(0.0, 0.125, 0)), f(0.25, 0.125), 1e-12);
}

TEST(CompareLines, VerticalAndHorizontalLinesThroughTheLoadCentre) {
  const auto g = grid2d();
  const auto lines = standard_lines(g, Eigen::Vector3d(2.0, 1.25, 0), {0.5});
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].name, "vertical");
  EXPECT_EQ(lines[0].samples, 5);
  EXPECT_DOUBLE_EQ(lines[0].point(0)[1], 1.125);
  EXPECT_DOUBLE_EQ(lines[0].point(4)[1], 0.125);
  EXPECT_DOUBLE_EQ(lines[0].point(2)[0], 2.0);
  EXPECT_EQ(lines[1].name, "depth_0.5");
  EXPECT_EQ(lines[1].samples, 8);
  EXPECT_DOUBLE_EQ(lines[1].point(0)[1], 0.625);
  EXPECT_DOUBLE_EQ(lines[1].point(7)[0], 3.75);
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
  EXPECT_EQ(relative_errors({0, 0}, {0, 0}).rel_l2, 0.0);
  EXPECT_TRUE(std::isinf(relative_errors({1, 0}, {0, 0}).rel_l2));
}
