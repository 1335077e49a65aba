// A grid laid out on tiles (agent::Tiles): the same body as the dense grid, slot for slot, with
// memory that follows the tiles its agents touch.
#include <agent/grid.h>

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

#include "../support/agent_fixtures.h"

using namespace agent;

namespace {

// A dense box of n cells per axis with a random half of its slots air, some faces rigid.
Grid random_body(int dim, std::array<int, 3> n, unsigned seed) {
  Grid g = Grid::box(dim, n, Eigen::Vector3d(0.5, 0.25, 2.0));
  std::mt19937 rng(seed);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (rng() % 2) g.make_air(c);
  std::vector<BoundaryFace> rigid;
  for (const auto& f : g.boundary_faces())
    if (rng() % 3 == 0) rigid.push_back(f);
  g.set_boundary(rigid, Boundary::Rigid);
  return g;
}

TEST(Tiles, SameBodySlotForSlot) {
  for (int dim : {2, 3}) {
    const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{150, 37, 1} : std::array<int, 3>{35, 17, 19};
    const Grid dense = random_body(dim, n, 7u + dim);
    const Grid tiled = tile(dense);
    ASSERT_TRUE(tiled.tiled());
    EXPECT_EQ(tiled.agent_count(), dense.agent_count());
    EXPECT_EQ(tiled.count() % 1024, 0u);
    for (std::size_t d = 0; d < dense.count(); ++d) {
      const auto c = dense.coords(d);
      const std::size_t t = tiled.index(c[0], c[1], c[2]);
      if (dense.is_air(d)) {
        if (t != Grid::npos) {
          EXPECT_TRUE(tiled.is_air(t));
        }
        continue;
      }
      ASSERT_NE(t, Grid::npos);
      EXPECT_EQ(tiled.coords(t), c);
      EXPECT_EQ(tiled.flags[t], dense.flags[d]);
      EXPECT_EQ(tiled.centre(t), dense.centre(d));
      for (int side = 0; side < 2 * dim; ++side) {
        EXPECT_EQ(tiled.has_neighbour(t, side), dense.has_neighbour(d, side));
        const std::size_t nd = dense.neighbour(d, side), nt = tiled.neighbour(t, side);
        if (nd == Grid::npos || dense.is_air(nd)) continue;
        EXPECT_EQ(tiled.coords(nt), dense.coords(nd));
      }
      // Every corner node of an agent is stored, at the dense grid's position.
      for (int corner = 0; corner < (dim == 2 ? 4 : 8); ++corner) {
        const std::array<int, 3> p{c[0] + (corner & 1), c[1] + ((corner >> 1) & 1), c[2] + ((corner >> 2) & 1)};
        const std::size_t node = tiled.node_index(p[0], p[1], p[2]);
        ASSERT_NE(node, Grid::npos);
        EXPECT_TRUE(tiled.is_grid_node(node));
        EXPECT_EQ(tiled.node_coords(node), p);
      }
    }
    // Slots of the tiles beyond the box are air; the boundary faces are the same faces.
    for (std::size_t t = 0; t < tiled.count(); ++t)
      if (!tiled.in_box(tiled.coords(t))) {
        EXPECT_TRUE(tiled.is_air(t));
      }
    EXPECT_EQ(tiled.boundary_faces().size(), dense.boundary_faces().size());
  }
}

// A diagonal staircase of 2000 steps: a 2001 x 2000 box holds 4000 agents. On tiles of 64 x 16,
// each band of 16 rows spans columns 16 b .. 16 b + 17 (agents and their corner nodes): one or
// two tiles along x, plus the band above for the top nodes.
TEST(Tiles, DiagonalStaircaseFollowsItsAgents) {
  const int steps = 2000;
  std::vector<std::array<int, 3>> agents;
  for (int s = 0; s < steps; ++s) {
    agents.push_back({s, s, 0});
    agents.push_back({s + 1, s, 0});
  }
  std::vector<std::int64_t> xs, ys;
  for (int s = 0; s <= steps; ++s) xs.push_back(s);
  for (int s = 0; s < steps; ++s) ys.push_back(s);
  const CompressedAxis ax(xs), ay(ys);
  const Grid g = Grid::lattice(2, {&ax, &ay, nullptr}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), agents);
  ASSERT_TRUE(g.tiled());
  EXPECT_EQ(g.cells, (std::array<int, 3>{steps + 1, steps, 1}));
  EXPECT_EQ(g.agent_count(), std::size_t(2 * steps));
  // By hand: node row y holds the corners of agent rows y and y - 1, x in [y - 1, y + 2]. Tile row
  // ty holds node rows 16 ty .. 16 ty + 15: x from 16 ty - 1 to 16 ty + 17, in tiles x / 64.
  std::size_t tiles = 0;
  for (int ty = 0; 16 * ty <= steps; ++ty) {
    const int y_hi = std::min(16 * ty + 15, steps);  // node rows 0 .. steps
    const int x_lo = std::max(16 * ty - 1, 0), x_hi = std::min(y_hi + 2, steps + 1);
    tiles += std::size_t(x_hi / 64 - x_lo / 64 + 1);
  }
  EXPECT_EQ(g.count(), tiles * 1024);
  EXPECT_LT(double(g.count()), 0.05 * double(g.cells[0]) * g.cells[1]);
  const auto layout = lattice_layout(2, g.cells, agents);
  EXPECT_TRUE(layout.tiled);
  EXPECT_EQ(layout.slots, double(g.count()));
  EXPECT_EQ(layout.tile_table, double(32 * 126));  // ceil(2002 / 64) x ceil(2001 / 16) tiles cover the nodes
  // A full box stays dense.
  std::vector<std::array<int, 3>> full;
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 70; ++i) full.push_back({i, j, 0});
  std::vector<std::int64_t> c70, c40;
  for (int i = 0; i < 70; ++i) c70.push_back(i);
  for (int j = 0; j < 40; ++j) c40.push_back(j);
  const CompressedAxis a70(c70), a40(c40);
  const Grid box = Grid::lattice(2, {&a70, &a40, nullptr}, Eigen::Vector3d::Zero(), Eigen::Vector3d::Ones(), full);
  EXPECT_FALSE(box.tiled());
  EXPECT_EQ(box.count(), 70u * 40u);
  EXPECT_EQ(box.agent_count(), 70u * 40u);
}

}  // namespace
