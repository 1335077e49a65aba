// Topology (seed steps 4a-4b), model building and the solver loop.
#include <pbd/model.h>
#include <pbd/solver.h>
#include <pbd/topology.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>

using pbd::Vec3;

namespace {

const double kPi = std::acos(-1.0);

/// The same mesh with its nodes renumbered by `perm` (new index of old node i is perm[i]).
pbd::Mesh renumber(const pbd::Mesh& m, const std::vector<int>& perm) {
  pbd::Mesh r = m;
  for (std::size_t i = 0; i < m.points.size(); ++i) r.points[perm[i]] = m.points[i];
  for (auto& v : r.cell_nodes) v = perm[v];
  return r;
}

double max_abs(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
  double m = 0;
  for (std::size_t i = 0; i < a.size(); ++i) m = std::max(m, (a[i] - b[i]).cwiseAbs().maxCoeff());
  return m;
}

}  // namespace

TEST(PbdTopology, RegularGridPartnerIsTheOppositeNeighbour) {
  for (bool triangles : {false, true}) {
    const auto mesh = pbd::Mesh::grid(4, 3, 0.5, triangles);
    const auto m = pbd::neighbour_sets(mesh.points.size(), pbd::mesh_edges(mesh));
    int checked = 0;
    for (int j = 1; j < 3; ++j)
      for (int i = 1; i < 4; ++i) {
        const int node = j * 5 + i;
        EXPECT_EQ(m[node].size(), triangles ? 6u : 4u);
        for (int k : m[node]) {
          const int best = pbd::max_angle_partner(mesh.points, node, m[node], k);
          ASSERT_GE(best, 0);
          EXPECT_LT((mesh.points[best] - (2 * mesh.points[node] - mesh.points[k])).norm(), 1e-12);
          EXPECT_DOUBLE_EQ(pbd::angle(mesh.points[best], mesh.points[k], mesh.points[node]), kPi);
          ++checked;
        }
      }
    EXPECT_EQ(checked, triangles ? 36 : 24);
  }
}

TEST(PbdTopology, TriplesAreDeduplicated) {
  // Polyline of 6 segments: 5 interior nodes, step 4b finds (k, best) and (best, k) at each.
  std::size_t raw = 0;
  auto line = pbd::Mesh::polyline(Vec3::Zero(), Vec3(6, 0, 0), 6);
  auto t = pbd::angle_triples(line.points, pbd::neighbour_sets(7, pbd::mesh_edges(line)), &raw);
  EXPECT_EQ(raw, 10u);
  EXPECT_EQ(t.size(), 5u);
  // 4 x 4 quads (5 x 5 nodes): interior 9 nodes x (4 raw, 2 kept), edge 12 x (3, 2), corners 4 x (2, 1).
  auto grid = pbd::Mesh::grid(4, 4, 1.0);
  t = pbd::angle_triples(grid.points, pbd::neighbour_sets(25, pbd::mesh_edges(grid)), &raw);
  EXPECT_EQ(raw, 9u * 4 + 12 * 3 + 4 * 2);
  EXPECT_EQ(t.size(), 9u * 2 + 12 * 2 + 4 * 1);
  std::set<std::tuple<int, int, int>> keys;
  for (const auto& c : t) keys.insert({c.i, std::min(c.k, c.best), std::max(c.k, c.best)});
  EXPECT_EQ(keys.size(), t.size());
}

TEST(PbdModel, SeedMassesAndLumpedMasses) {
  const auto line = pbd::Mesh::polyline(Vec3::Zero(), Vec3(1, 0, 0), 4);
  pbd::ModelOptions o;  // seed: m_i = 1/n
  auto m = pbd::build_model(line, {}, o);
  for (double w : m.particles.w) EXPECT_DOUBLE_EQ(w, 5.0);
  o.masses = pbd::ModelOptions::Masses::Lumped;
  o.total_mass = 2.0;
  m = pbd::build_model(line, {0}, o);
  EXPECT_EQ(m.particles.w[0], 0.0);
  EXPECT_DOUBLE_EQ(1 / m.particles.w[1], 0.5);
  EXPECT_DOUBLE_EQ(1 / m.particles.w[4], 0.25);
}

TEST(PbdModel, BendingComplianceFromEIIsHalvedAtAClamp) {
  // ghost - clamp - 1 - 2: the angle at the clamp node counts only half its inner edge.
  const auto line = pbd::Mesh::polyline(Vec3(-0.5, 0, 0), Vec3(1, 0, 0), 3);
  pbd::ModelOptions o;
  o.bending_stiffness = 2.0;
  const auto m = pbd::build_model(line, {0, 1}, o);
  ASSERT_EQ(m.angles.size(), 2u);
  std::vector<double> c;
  for (const auto& a : m.angles) c.push_back(a.compliance);
  std::sort(c.begin(), c.end());
  EXPECT_DOUBLE_EQ(c[0], 0.25 / 2.0);  // at the clamp: l/2 / EI
  EXPECT_DOUBLE_EQ(c[1], 0.5 / 2.0);   // interior: l / EI
}

TEST(PbdModel, BlocksOfAColourShareNoParticle) {
  const auto mesh = pbd::Mesh::grid(40, 30, 0.1, true);
  pbd::ModelOptions o;
  o.block_size = 16;
  const auto m = pbd::build_model(mesh, {0, 1, 2}, o);
  auto check = [](const pbd::Colouring& col, std::size_t count, auto nodes_of) {
    EXPECT_EQ(col.block_begin.back(), count);
    EXPECT_EQ(col.colour_begin.back(), col.blocks());
    EXPECT_GT(col.colours(), 1u);
    EXPECT_LE(col.colours(), 8u);  // blocks along rows: few colours
    for (std::size_t c = 0; c < col.colours(); ++c) {
      std::set<int> seen;
      for (std::size_t b = col.colour_begin[c]; b < col.colour_begin[c + 1]; ++b) {
        std::set<int> mine;
        for (std::size_t k = col.block_begin[b]; k < col.block_begin[b + 1]; ++k)
          for (int p : nodes_of(k)) mine.insert(p);
        for (int p : mine) EXPECT_TRUE(seen.insert(p).second) << "colour " << c << " particle " << p;
      }
    }
  };
  check(m.distance_colouring, m.distances.size(),
        [&](std::size_t k) { return std::vector<int>{m.distances[k].a, m.distances[k].b}; });
  check(m.angle_colouring, m.angles.size(),
        [&](std::size_t k) { return std::vector<int>{m.angles[k].best, m.angles[k].k, m.angles[k].i}; });
}

TEST(PbdSolver, MeshAtRestStaysAtRest) {
  // A perturbed (non-straight rest angles) triangulated sheet in 3D and a curved planar rod, no
  // external load: nothing may move.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.02, 0.02);
  auto sheet = pbd::Mesh::grid(6, 5, 0.1, true);
  for (auto& p : sheet.points) p += Vec3(u(rng), u(rng), u(rng));
  auto rod = pbd::Mesh::polyline(Vec3::Zero(), Vec3(1, 0, 0), 10);
  for (auto& p : rod.points) p[1] = 0.3 * std::sin(3 * p[0]);
  for (auto* mesh : {&sheet, &rod}) {
    pbd::ModelOptions o;
    o.bending_compliance = 1e-3;
    if (mesh == &rod) o.planar_axis = Vec3::UnitZ();
    auto model = pbd::build_model(*mesh, {}, o);
    pbd::Solver solver(model);
    pbd::StepSettings s;
    s.gravity.setZero();
    s.substeps = 4;
    s.iterations = 2;
    for (int f = 0; f < 30; ++f) solver.step(s);
    EXPECT_LT(max_abs(model.particles.x, mesh->points), 1e-13);
  }
}

TEST(PbdSolver, InternalConstraintsConserveMomentum) {
  // Free bent rod in 3D and a free sheet with random velocities, no gravity, no damping.
  std::mt19937 rng(8);
  std::normal_distribution<double> n(0, 1);
  auto sheet = pbd::Mesh::grid(5, 4, 0.1, true);
  for (auto& p : sheet.points) p[2] = 0.05 * std::sin(10 * p[0]);
  pbd::ModelOptions o;
  o.masses = pbd::ModelOptions::Masses::Lumped;
  o.bending_compliance = 1e-2;
  o.stretch_compliance = 1e-4;
  auto model = pbd::build_model(sheet, {}, o);
  for (auto& v : model.particles.v) v = Vec3(n(rng), n(rng), n(rng));
  const Vec3 p0 = model.particles.momentum();
  const Vec3 c0 = model.particles.mass_moment();
  pbd::Solver solver(model);
  pbd::StepSettings s;
  s.gravity.setZero();
  s.dt = 0.01;
  s.substeps = 3;
  s.iterations = 2;
  for (int f = 0; f < 50; ++f) solver.step(s);
  const Vec3 p1 = model.particles.momentum();
  EXPECT_LT((p1 - p0).norm(), 1e-12 * (1 + p0.norm()));
  // The centre of mass moves uniformly: m x_c(t) = m x_c(0) + p t.
  EXPECT_LT((model.particles.mass_moment() - (c0 + p0 * 0.5)).norm(), 1e-11);
  EXPECT_GT(solver.residuals().angle, 0.0);  // the constraints did act (compliant, bent)
}

TEST(PbdSolver, GravityIsAnAcceleration) {
  // Free fall: every node falls g t^2 / 2 (up to the symplectic Euler offset) on any mesh size.
  for (int n : {4, 40}) {
    auto rod = pbd::Mesh::polyline(Vec3::Zero(), Vec3(1, 0, 0), n);
    auto model = pbd::build_model(rod, {}, {});
    pbd::Solver solver(model);
    pbd::StepSettings s;
    s.dt = 0.01;
    for (int f = 0; f < 100; ++f) solver.step(s);
    // symplectic Euler: y = -g dt^2 * sum_{k=1}^{100} k
    EXPECT_NEAR(model.particles.x[n / 2][1], -9.81 * 1e-4 * 5050, 1e-9);
  }
}

TEST(PbdSolver, ResultsDoNotDependOnNodeNumbering) {
  // A sheet clamped along one edge, sagging in 3D (unsigned form), and the same sheet renumbered.
  auto sheet = pbd::Mesh::grid(8, 5, 0.1, true);
  std::vector<int> pinned;
  for (int j = 0; j <= 5; ++j) pinned.push_back(j * 9);
  std::vector<int> perm(sheet.points.size());
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(9));
  const auto other = renumber(sheet, perm);
  std::vector<int> other_pinned;
  for (int p : pinned) other_pinned.push_back(perm[p]);
  pbd::ModelOptions o;
  o.masses = pbd::ModelOptions::Masses::Lumped;
  o.bending_compliance = 1e-2;
  auto a = pbd::build_model(sheet, pinned, o), b = pbd::build_model(other, other_pinned, o);
  ASSERT_EQ(a.angles.size(), b.angles.size());
  pbd::Solver sa(a), sb(b);
  pbd::StepSettings s;
  s.gravity = Vec3(0, 0, -9.81);
  s.substeps = 3;
  s.iterations = 2;
  for (int f = 0; f < 20; ++f) {
    sa.step(s);
    sb.step(s);
  }
  double diff = 0;
  for (std::size_t i = 0; i < perm.size(); ++i) diff = std::max(diff, (a.particles.x[i] - b.particles.x[perm[i]]).norm());
  EXPECT_LT(diff, 1e-12);
  EXPECT_GT((a.particles.x.back() - sheet.points.back()).norm(), 1e-3);  // it did sag
}

TEST(PbdSolver, ParallelColoursGiveTheSerialResult) {
  if (!pbd::Solver::parallel_available()) GTEST_SKIP() << "built without OpenMP: threads > 1 runs the serial path";
  auto sheet = pbd::Mesh::grid(24, 16, 0.05, true);
  std::vector<int> pinned;
  for (int j = 0; j <= 16; ++j) pinned.push_back(j * 25);
  pbd::ModelOptions o;
  o.bending_compliance = 1e-3;
  o.block_size = 8;  // many blocks per colour
  auto a = pbd::build_model(sheet, pinned, o), b = a;
  pbd::Solver sa(a), sb(b);
  pbd::StepSettings s;
  s.gravity = Vec3(0, 0, -9.81);
  s.substeps = 2;
  for (int f = 0; f < 5; ++f) {
    s.threads = 1;
    sa.step(s);
    s.threads = 2;
    sb.step(s);
  }
  EXPECT_EQ(max_abs(a.particles.x, b.particles.x), 0.0);
}

TEST(PbdSolver, EveryThreadCountGivesThePlainGaussSeidelLoopBitwise) {
  // The solver against the plain loop it stands for: per substep prediction, `iterations` sweeps
  // over the distance then the angle constraints in array order with multipliers reset to 0,
  // velocities from the positions. The solver reads the multipliers only between sweeps, splits
  // colours among threads and has each thread predict its own particles: none of it may change a
  // bit, for any thread count, iteration count or form.
  for (bool planar : {false, true})
    for (int iterations : {1, 3}) {
      auto sheet = pbd::Mesh::grid(20, 13, 0.05, true);
      if (!planar)
        for (auto& p : sheet.points) p[2] = 0.01 * std::sin(9 * p[0]) * std::cos(7 * p[1]);
      std::vector<int> pinned;
      for (int j = 0; j <= 13; ++j) pinned.push_back(j * 21);
      pbd::ModelOptions o;
      o.bending_compliance = 1e-3;
      o.stretch_compliance = 1e-7;
      o.block_size = 8;
      if (planar) o.planar_axis = Vec3::UnitZ();
      const auto start = pbd::build_model(sheet, pinned, o);
      pbd::StepSettings s;
      s.gravity = planar ? Vec3(0, -9.81, 0) : Vec3(0, 0, -9.81);
      s.node_force = Vec3(0.01, 0.02, 0.03);
      s.damping = 0.5;
      s.substeps = 2;
      s.iterations = iterations;
      const int frames = 6;

      auto ref = start;
      auto& P = ref.particles;
      std::vector<double> ld(ref.distances.size()), la(ref.angles.size());
      const double h = s.dt / s.substeps, keep = std::exp(-s.damping * h), inv_h2 = 1.0 / (h * h);
      for (int k = 0; k < frames * s.substeps; ++k) {
        for (std::size_t i = 0; i < P.size(); ++i) {
          P.x_prev[i] = P.x[i];
          if (P.w[i] == 0) {
            P.v[i].setZero();
            continue;
          }
          P.v[i] += h * (s.gravity + P.w[i] * s.node_force);
          P.x[i] += h * P.v[i];
        }
        std::fill(ld.begin(), ld.end(), 0.0);
        std::fill(la.begin(), la.end(), 0.0);
        for (int it = 0; it < iterations; ++it) {
          for (std::size_t c = 0; c < ref.distances.size(); ++c) {
            const auto& d = ref.distances[c];
            pbd::project_distance(P.x[d.a], P.x[d.b], P.w[d.a], P.w[d.b], d.rest, d.compliance * inv_h2, ld[c]);
          }
          for (std::size_t c = 0; c < ref.angles.size(); ++c) {
            const auto& a = ref.angles[c];
            pbd::project_angle(P.x[a.best], P.x[a.k], P.x[a.i], P.w[a.best], P.w[a.k], P.w[a.i], a.rest_cos,
                               a.rest_sin, a.compliance * inv_h2, la[c], ref.axis_ptr());
          }
        }
        for (std::size_t i = 0; i < P.size(); ++i)
          if (P.w[i] != 0) P.v[i] = (P.x[i] - P.x_prev[i]) * (keep / h);
      }
      ASSERT_GT(max_abs(P.x, start.particles.x), 1e-4);  // it moved

      for (int threads : {1, 2, 3}) {
        if (threads > 1 && !pbd::Solver::parallel_available()) continue;
        auto m = start;
        pbd::Solver solver(m);
        s.threads = threads;
        for (int f = 0; f < frames; ++f) solver.step(s);
        EXPECT_EQ(max_abs(m.particles.x, P.x), 0.0) << "threads " << threads << " iterations " << iterations;
        EXPECT_EQ(max_abs(m.particles.v, P.v), 0.0) << "threads " << threads << " iterations " << iterations;
        EXPECT_EQ(max_abs(m.particles.x_prev, P.x_prev), 0.0) << "threads " << threads;
      }
    }
}

TEST(PbdSolver, FlatSheetOnTheStraightSingularityStaysFinite) {
  // Every rest angle of a regular grid is pi (the notes' trap): a sheet pushed out of its plane
  // must stay finite in both forms.
  for (bool planar : {false, true}) {
    auto sheet = pbd::Mesh::grid(10, 10, 0.1);
    pbd::ModelOptions o;
    if (planar) o.planar_axis = Vec3::UnitZ();
    auto model = pbd::build_model(sheet, {0, 10}, o);
    pbd::Solver solver(model);
    pbd::StepSettings s;
    s.gravity = planar ? Vec3(0, -9.81, 0) : Vec3(0, 0, -9.81);
    for (int f = 0; f < 30; ++f) solver.step(s);
    for (const auto& x : model.particles.x) ASSERT_TRUE(x.allFinite());
  }
}

TEST(PbdSolver, ClampedRodSmokeTest) {
  // The validation rod (tests/pbd/test_validation.cc) at N = 10, cheap enough for the sanitizer
  // build: E I = 1, rho A = 1, L = 1, q = 0.008, clamp by a pinned ghost node.
  const int N = 10;
  const double l = 1.0 / N;
  const auto mesh = pbd::Mesh::polyline(Vec3(-l, 0, 0), Vec3(1, 0, 0), N + 1);
  pbd::ModelOptions o;
  o.masses = pbd::ModelOptions::Masses::Lumped;
  o.bending_stiffness = 1.0;
  o.planar_axis = Vec3::UnitZ();
  auto model = pbd::build_model(mesh, {0, 1}, o);
  pbd::Solver solver(model);
  pbd::StepSettings s;
  s.dt = 0.01;
  s.substeps = 5;
  s.iterations = 4;
  s.gravity = Vec3(0, -0.008, 0);
  s.damping = 2 * 3.516;
  for (int f = 0; f < 400; ++f) solver.step(s);
  // Euler-Bernoulli: 1e-3; the N = 10 chain is 1.0 % softer (converges as 1/N^2).
  EXPECT_NEAR(-model.particles.x.back()[1], 1.00998e-3, 2e-7);
}
