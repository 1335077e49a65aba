// The slot layouts (agent/slots.h) and the LoadTransfer facade: DenseSlots and TiledSlots name the
// same slots, the facade refuses readings with a rule set they do not belong to, the stress
// readings apply to any rule set's face forces, and memory_bytes() counts the tile table.
#include <agent/fields.h>
#include <agent/load_transfer.h>
#include <agent/slots.h>

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>

#include "../support/agent_fixtures.h"

using namespace agent;
using namespace test_support;

namespace {

// A dense box with a random third of its slots air.
Grid holey(int dim, std::array<int, 3> n, unsigned seed) {
  Grid g = Grid::box(dim, n, Eigen::Vector3d(1, 1, 1));
  std::mt19937 rng(seed);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (rng() % 3 == 0) g.make_air(c);
  return g;
}

TEST(Slots, DenseAndTiledNameTheSameSlotsAlongEveryAxis) {
  for (int dim : {2, 3}) {
    const std::array<int, 3> n = dim == 2 ? std::array<int, 3>{70, 20, 1} : std::array<int, 3>{18, 9, 10};
    const Grid dense = holey(dim, n, 3u + dim), tiled = tile(dense);
    ASSERT_TRUE(tiled.tiled());
    const DenseSlots ds(dense);
    const TiledSlots ts(tiled);
    for (int a = 0; a < dim; ++a) {
      const auto lat = lateral_axes(a);
      for (int layer = 0; layer < n[a]; ++layer)
        for (int v = 0; v < n[lat.l1]; ++v) {
          const auto drow = ds.layer(a, layer).row(v);
          const auto trow = ts.layer(a, layer).row(v);
          for (int u = 0; u < n[lat.l0]; ++u) {
            std::array<int, 3> c{};
            c[a] = layer;
            c[lat.l0] = u;
            c[lat.l1] = v;
            const std::size_t d = drow(u), t = trow(u);
            ASSERT_EQ(d, dense.index(c[0], c[1], c[2]));
            ASSERT_EQ(d, ds.layer(a, layer)(u, v));
            ASSERT_EQ(t, tiled.index(c[0], c[1], c[2]));
            ASSERT_EQ(t, ts.layer(a, layer)(u, v));
            EXPECT_EQ(ds.air(d), ts.air(t)) << a << ": " << c[0] << "," << c[1] << "," << c[2];
            if (ds.air(d)) continue;
            for (int side = 0; side < 2 * dim; ++side) EXPECT_EQ(ds.rigid(d, side), ts.rigid(t, side));
            // One step along each axis inside the box: the same slot in both layouts.
            for (int b = 0; b < dim; ++b)
              for (int sgn : {-1, 1}) {
                std::array<int, 3> x = c;
                x[b] += sgn;
                if (!dense.in_box(x)) continue;
                EXPECT_EQ(ds.lane(b).next(d, sgn), dense.index(x[0], x[1], x[2]));
                const std::size_t next = ts.lane(b).next(t, sgn);
                EXPECT_EQ(next, tiled.index(x[0], x[1], x[2]));
              }
          }
          // The runs of a row cover exactly its stored ids, in order.
          std::vector<std::size_t> listed, stored;
          trow.runs(0, n[lat.l0] - 1, [&](std::size_t first, std::size_t count) {
            for (std::size_t i = 0; i < count; ++i) listed.push_back(first + i);
          });
          for (int u = 0; u < n[lat.l0]; ++u)
            if (trow(u) != Grid::npos) stored.push_back(trow(u));
          EXPECT_EQ(listed, stored);
          listed.clear();
          drow.runs(2, n[lat.l0] - 2, [&](std::size_t first, std::size_t count) {
            for (std::size_t i = 0; i < count; ++i) listed.push_back(first + i * (a == 0 ? dense.stride(1) : 1));
          });
          ASSERT_EQ(listed.size(), std::size_t(n[lat.l0] - 3));
          EXPECT_EQ(listed.front(), drow(2));
        }
    }
  }
}

TEST(Slots, TheFacadeRefusesAReadingWithARuleSetItDoesNotBelongTo) {
  const Grid g = plate(4, 4);
  TransferReadings once;
  once.non_compounding_entry = true;
  TransferReadings cyclic;
  cyclic.every_agent_all_operations = true;
  for (RuleSet rules : {RuleSet::Conserving, RuleSet::Directional}) {
    EXPECT_THROW(LoadTransfer(g, kMaterial, Coefficients{}, rules, once), std::invalid_argument);
    EXPECT_THROW(LoadTransfer(g, kMaterial, Coefficients{}, rules, cyclic), std::invalid_argument);
  }
  EXPECT_NO_THROW(LoadTransfer(g, kMaterial, Coefficients{}, RuleSet::Patent, once));
  // The stress readings are not the transfer's: a Readings converts, and the transfer is the same.
  Readings stress;
  stress.entering_face_stress = stress.lateral_strain_stress = true;
  for (RuleSet rules : {RuleSet::Patent, RuleSet::Conserving, RuleSet::Directional}) {
    LoadTransfer with(g, kMaterial, Coefficients{}, rules, stress), without(g, kMaterial, Coefficients{}, rules);
    with.solve({{g.index(1, 3, 0), kMinusY, 2.0}});
    without.solve({{g.index(1, 3, 0), kMinusY, 2.0}});
    EXPECT_EQ(with.face_forces(), without.face_forces());
  }
}

TEST(Slots, StressReadingsApplyToTheConservingRuleSetsFaces) {
  // One agent column of two under 2 N, conserving, no friction: every TOP carries 2 N.
  const Grid g = plate(1, 2);
  LoadTransfer m(g, kMaterial, coefficients(0.5, 0.5, 0.0, 1.0, 1e-9), RuleSet::Conserving);
  m.solve({{g.index(0, 1, 0), kMinusY, 2.0}});
  StressReadings r;
  r.entering_face_stress = r.lateral_strain_stress = true;
  const auto s = agent_stresses(g, m.face_forces(), r, kMinusY, 0.5, 0.3);
  EXPECT_DOUBLE_EQ(s[1 * 2 + 1], -2.0);          // sigma_y of the top agent: -F_top / A
  EXPECT_DOUBLE_EQ(s[1 * 2 + 0], 0.5 * 0.3 * 2.0);  // sigma_x = -beta nu sigma_y: tension
}

TEST(Slots, MemoryBytesCountsTheTileTable) {
  // The same body, dense and tiled: on tiles the solver's bytes are its slots' plus the table's.
  Grid dense = Grid::box(2, {300, 300, 1}, Eigen::Vector3d(1, 1, 1));
  for (std::size_t c = 0; c < dense.count(); ++c) {
    const auto x = dense.coords(c);
    if (x[0] != x[1]) dense.make_air(c);
  }
  dense.set_boundary(dense.box_side(kMinusY), Boundary::Rigid);
  const Grid tiled = tile(dense);
  ASSERT_TRUE(tiled.tiled());
  const LoadTransfer m(tiled, kMaterial, Coefficients{}, RuleSet::Directional);
  // Directional holds no scratch: results (4 forces, a shear, a generation) and a flag per slot, two
  // moment-balance slopes per layer across each axis of the box (300 + 300 + 1), and the table: 5 x 19 tiles of 4 B, and 3
  // ints per stored tile.
  const std::size_t slots = tiled.count();
  EXPECT_EQ(tiled.tiles.number.size(), 5u * 19u);
  const Tiles& t = m.grid().tiles;
  EXPECT_EQ(m.memory_bytes(), slots * (5 * 8 + 4 + 1) + 2 * (300 + 300 + 1) * 8 + t.number.capacity() * 4 + t.first.capacity() * 12);
}

}  // namespace
