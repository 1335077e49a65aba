// Every rule set and the fields on a grid laid out on tiles: the same face forces, generations,
// tallies, stresses, strains and node displacements as on the dense grid of the same body, bit
// for bit, and memory that follows the tiles.
#include <agent/fields.h>
#include <agent/load_transfer.h>

#include <gtest/gtest.h>

#include <random>

#include "../support/agent_fixtures.h"

using namespace agent;

namespace {

// A dense box with a ring-shaped hole, a notch and a random tenth of its slots air; a random third
// of its boundary faces rigid.
Grid holey_body(int dim, std::array<int, 3> n, unsigned seed) {
  Grid g = Grid::box(dim, n, Eigen::Vector3d(0.5, 0.25, 2.0));
  std::mt19937 rng(seed);
  for (std::size_t c = 0; c < g.count(); ++c) {
    const auto x = g.coords(c);
    const double dx = x[0] - 0.5 * n[0], dy = x[1] - 0.5 * n[1];
    const bool hole = dx * dx + dy * dy < 0.08 * n[0] * n[1];
    const bool notch = x[0] < n[0] / 3 && x[1] > n[1] / 2 && x[1] < n[1] / 2 + 3;
    if (hole || notch || rng() % 10 == 0) g.make_air(c);
  }
  std::vector<BoundaryFace> rigid;
  for (const auto& f : g.boundary_faces())
    if (rng() % 3 == 0) rigid.push_back(f);
  g.set_boundary(rigid, Boundary::Rigid);
  return g;
}

// A connected but sparse body: a diagonal band 12 agents wide (3D: 6 deep) across the box, so
// that most tiles of the box are not stored; a random third of its boundary faces rigid.
Grid band_body(int dim, std::array<int, 3> n, unsigned seed) {
  Grid g = Grid::box(dim, n, Eigen::Vector3d(0.5, 0.25, 2.0));
  for (std::size_t c = 0; c < g.count(); ++c) {
    const auto x = g.coords(c);
    if (std::abs(x[0] - 2 * x[1]) >= 6 || (dim == 3 && std::abs(2 * x[2] - n[2]) >= 6)) g.make_air(c);
  }
  std::mt19937 rng(seed);
  std::vector<BoundaryFace> rigid;
  for (const auto& f : g.boundary_faces())
    if (rng() % 3 == 0) rigid.push_back(f);
  g.set_boundary(rigid, Boundary::Rigid);
  return g;
}

// Four test bodies: a holey box in 2D (body 0) and 3D (1), a sparse band in 2D (2) and 3D (3);
// `scale` enlarges them.
Grid test_body(int body, int scale, unsigned seed) {
  const int dim = body % 2 ? 3 : 2;
  const std::array<int, 3> n = body >= 2 ? (dim == 2 ? std::array<int, 3>{100 * scale, 50 * scale, 1} : std::array<int, 3>{50, 25, 24})
                                         : (dim == 2 ? std::array<int, 3>{75 * scale, 35 * scale, 1} : std::array<int, 3>{20, 18, 17});
  return body >= 2 ? band_body(dim, n, seed + dim) : holey_body(dim, n, seed + dim);
}

// Entry loads on a few agents per direction (every direction, so each axis is the load's once),
// each on an agent whose face the load enters by is a boundary face.
std::vector<EntryLoad> loads_for(const Grid& g, unsigned seed) {
  std::vector<EntryLoad> loads;
  std::mt19937 rng(seed);
  for (int dir = 0; dir < 2 * g.dim; ++dir) {
    int placed = 0;
    for (const auto& f : g.boundary_faces())
      if (f.side == opposite(dir) && rng() % 7 == 0 && placed < 3) {
        loads.push_back({f.cell, dir, 1.0 + 0.25 * placed});
        ++placed;
      }
  }
  return loads;
}

// The dense grid's loads on the tiled grid (the same agents by box coordinates).
std::vector<EntryLoad> on_tiles(const Grid& dense, const Grid& tiled, std::vector<EntryLoad> loads) {
  for (auto& l : loads) {
    const auto c = dense.coords(l.cell);
    l.cell = tiled.index(c[0], c[1], c[2]);
  }
  return loads;
}

void expect_same(const LoadTransfer& dense, const LoadTransfer& tiled, const std::string& what) {
  const Grid &gd = dense.grid(), &gt = tiled.grid();
  const int nd = 2 * gd.dim;
  EXPECT_EQ(test_support::in_dense_order(gd, gt, tiled.face_forces(), nd, 0.0), dense.face_forces()) << what;
  EXPECT_EQ(test_support::in_dense_order(gd, gt, tiled.generation(), 1, -1), dense.generation()) << what;
  const Diagnostics &a = dense.diagnostics(), &b = tiled.diagnostics();
  EXPECT_EQ(a.agents_generated, b.agents_generated) << what;
  EXPECT_EQ(a.agent_updates, b.agent_updates) << what;
  EXPECT_EQ(a.applied, b.applied) << what;
  EXPECT_EQ(a.rigid_reaction, b.rigid_reaction) << what;
  EXPECT_EQ(a.passed_out, b.passed_out) << what;
  EXPECT_EQ(a.dropped, b.dropped) << what;
  EXPECT_EQ(a.lost, b.lost) << what;
  EXPECT_EQ(a.lateral_reaction, b.lateral_reaction) << what;
  EXPECT_EQ(a.lateral_passed_out, b.lateral_passed_out) << what;
  EXPECT_EQ(a.lateral_dropped, b.lateral_dropped) << what;
  EXPECT_EQ(a.packet_moves, b.packet_moves) << what;
  EXPECT_EQ(a.returned_rigid, b.returned_rigid) << what;
  EXPECT_EQ(a.returned_free, b.returned_free) << what;
  EXPECT_GT(a.agents_generated, 50u) << what;  // the loads went somewhere
}

TEST(TiledSweep, SameFacesGenerationsAndTalliesAsTheDenseGrid) {
  for (int dim : {2, 3}) {
    const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{150, 70, 1} : std::array<int, 3>{34, 30, 21};
    const Grid dense = holey_body(dim, n, 11u + dim);
    const Grid tiled = tile(dense);
    ASSERT_TRUE(tiled.tiled());
    const auto loads = loads_for(dense, 3u + dim), later = loads_for(dense, 5u + dim);
    struct Variant {
      RuleSet rules;
      bool reading1;
    };
    for (const Variant v : {Variant{RuleSet::Patent, false}, Variant{RuleSet::Patent, true}, Variant{RuleSet::Conserving, false}}) {
      Readings r;
      r.non_compounding_entry = v.reading1;
      const Coefficients k = test_support::coefficients(0.9, 0.8, 0.15, 0.5, 1e-6);
      LoadTransfer md(dense, test_support::kMaterial, k, v.rules, r), mt(tiled, test_support::kMaterial, k, v.rules, r);
      const std::string what = std::to_string(dim) + "D " + rule_set_name(v.rules) + (v.reading1 ? " reading 1" : "");
      md.solve(loads);
      mt.solve(on_tiles(dense, tiled, loads));
      expect_same(md, mt, what);
      // A second solve clears what the first wrote: along one axis (the lazy clearing, layer by
      // layer), then along all.
      const std::vector<EntryLoad> one_axis(later.begin(), later.begin() + 2);
      md.solve(one_axis);
      mt.solve(on_tiles(dense, tiled, one_axis));
      expect_same(md, mt, what + ", second solve");
      md.solve(later);
      mt.solve(on_tiles(dense, tiled, later));
      expect_same(md, mt, what + ", third solve");
    }
  }
}

TEST(TiledTransfer, CyclicAndDirectionalRuleSetsAsOnTheDenseGrid) {
  for (int body = 0; body < 4; ++body) {
    const Grid dense = test_body(body, 2, 21u);
    const int dim = dense.dim;
    const Grid tiled = tile(dense);
    const auto loads = loads_for(dense, 9u + dim);
    for (int variant = 0; variant < 4; ++variant) {
      Readings r;
      r.every_agent_all_operations = variant == 0 || variant == 2;
      r.boundaries_return = variant == 1 || variant == 2;
      const RuleSet rules = variant == 3 ? RuleSet::Directional : RuleSet::Patent;
      const Coefficients k = variant == 3 ? Coefficients{} : test_support::coefficients(0.5, 0.5, 0.2, 0.9, 1e-3);
      LoadTransfer md(dense, test_support::kMaterial, k, rules, r), mt(tiled, test_support::kMaterial, k, rules, r);
      const std::string what = std::to_string(dim) + "D body " + std::to_string(body) + " variant " + std::to_string(variant);
      md.solve(loads);
      mt.solve(on_tiles(dense, tiled, loads));
      expect_same(md, mt, what);
    }
  }
}

TEST(TiledTransfer, StressesStrainsDatumsAndNodeDisplacementsAsOnTheDenseGrid) {
  for (int body = 0; body < 4; ++body) {
    const Grid dense = test_body(body, 3, 31u);
    const int dim = dense.dim, sparse = body >= 2;
    const auto& n = dense.cells;
    const Grid tiled = tile(dense);
    const auto loads = loads_for(dense, 13u + dim);
    const Coefficients k = test_support::coefficients(0.9, 0.8, 0.15, 0.5, 1e-6);
    LoadTransfer md(dense, test_support::kMaterial, k, RuleSet::Patent), mt(tiled, test_support::kMaterial, k, RuleSet::Patent);
    md.solve(loads);
    const auto tiled_loads = on_tiles(dense, tiled, loads);
    mt.solve(tiled_loads);
    const auto sd = agent_stresses(dense, md.face_forces()), st = agent_stresses(tiled, mt.face_forces());
    EXPECT_EQ(test_support::in_dense_order(dense, tiled, st, dim, 0.0), sd);
    const auto ed = agent_strains(dense, test_support::kMaterial, sd), et = agent_strains(tiled, test_support::kMaterial, st);
    EXPECT_EQ(test_support::in_dense_order(dense, tiled, et, 3, 0.0), ed);
    const Datums dd = choose_datums(dense, loads), dt = choose_datums(tiled, tiled_loads);
    EXPECT_EQ(dd, dt);
    // The datum inside the body (the force-weighted centre) as well as at a rigid face.
    for (const Datums datums : {dd, Datums{0.37 * n[0], 0.61 * n[1], 0.5 * n[2]}}) {
      const auto ud = node_displacements(dense, ed, datums), ut = node_displacements(tiled, et, datums);
      const auto ut_dense = test_support::in_dense_order(dense, tiled, ut, dim, 0.0, true);
      // Every node a stored tile holds has the dense grid's value; the others are nodes of air only.
      std::size_t compared = 0;
      for (std::size_t node = 0; node < dense.node_count(); ++node) {
        const auto p = dense.node_coords(node);
        if (tiled.node_index(p[0], p[1], p[2]) == Grid::npos) continue;
        ++compared;
        for (int c = 0; c < dim; ++c) ASSERT_EQ(ut_dense[node * dim + c], ud[node * dim + c]) << dim << "D node " << node;
      }
      if (sparse) {
        EXPECT_LT(double(compared), 0.6 * double(dense.node_count()));  // most tiles are air
      } else {
        EXPECT_EQ(compared, dense.node_count());  // this body touches every tile
      }
      double largest = 0;
      for (double x : ud) largest = std::max(largest, std::abs(x));
      EXPECT_GT(largest, 0.0);
    }
  }
}

// The 2000-step diagonal staircase (tests/agent/test_tiles.cc): a 2001 x 2000 box, 4000 agents,
// 188 tiles of 1024 slots. Dense, the solver holds 37 B a slot (4 face forces, a generation, a
// flag byte): 148 MB; on tiles 192,512 slots, 7.1 MB, plus the three layer buffers of one row of
// the box (3 x 2001 x 8 B) and the line buffer: under 7.3 MB.
TEST(TiledSweep, AStaircaseHoldsItsTilesNotItsBox) {
  const int steps = 2000;
  Grid dense = Grid::box(2, {steps + 1, steps, 1}, Eigen::Vector3d::Ones());
  for (std::size_t c = 0; c < dense.count(); ++c) {
    const auto x = dense.coords(c);
    if (x[0] != x[1] && x[0] != x[1] + 1) dense.make_air(c);
  }
  dense.set_boundary(dense.box_side(test_support::kMinusY), Boundary::Rigid);
  const Grid tiled = tile(dense);
  ASSERT_EQ(tiled.count(), 188u * 1024u);
  const Coefficients k = test_support::coefficients(0.9, 0.8, 0.15, 0.5, 1e-9);
  LoadTransfer md(dense, test_support::kMaterial, k, RuleSet::Patent), mt(tiled, test_support::kMaterial, k, RuleSet::Patent);
  const std::vector<EntryLoad> load{{dense.index(steps, steps - 1, 0), direction(1, false), 1.0}};
  md.solve(load);
  mt.solve(on_tiles(dense, tiled, load));
  EXPECT_EQ(test_support::in_dense_order(dense, tiled, mt.face_forces(), 4, 0.0), md.face_forces());
  EXPECT_GT(md.memory_bytes(), std::size_t(4002000) * 37);
  EXPECT_LT(mt.memory_bytes(), std::size_t(7300000));
}

}  // namespace
