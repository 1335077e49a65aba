// The directional rule set's turning paths and its stress components (agent/stress_components.h):
// closed forms of the tie scan, each row's force conserved, the load balance, the symmetry of a
// centred load, and the rigid face holding zero displacement.
#include <agent/directional.h>
#include <agent/fields.h>
#include <agent/layer_stresses.h>
#include <agent/load_transfer.h>
#include <agent/stress_components.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <utility>

#include "../support/agent_fixtures.h"

using namespace agent;
using namespace test_support;  // plate, face, kMaterial, the face directions

namespace {

/// The seed plate's shape at test size: nx x ny agents of 5 mm, 2 mm thick, steel, rigid base.
Grid steel_plate(int nx, int ny, bool rigid_base = true) {
  Grid g = Grid::box(2, {nx, ny, 1}, Eigen::Vector3d(5e-3, 5e-3, 5e-3), 2e-3);
  if (rigid_base) g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  return g;
}

const Material kSteel{206e9, 0.3};

/// Everything the agents give for `loads` (as agent_study::evaluate does, the readings off).
struct Fields {
  LoadTransfer model;
  StressComponents stress;
  std::vector<double> u;
};

Fields solve(const Grid& g, const Coefficients& k, const std::vector<EntryLoad>& loads) {
  LoadTransfer m(g, kSteel, k, RuleSet::Directional);
  m.solve(loads);
  const auto normal = agent_stresses(g, m.face_forces());
  auto stress = directional_stress_components(g, normal, m.shear_stress(), m.balance_slopes(), k.directional, kSteel.poisson, loads);
  const auto strain = agent_strains(g, kSteel, stress.sigma);
  auto u = node_displacements_marched(g, strain, stress.shear, kSteel, choose_datums(g, loads), 1);
  hold_rigid_faces(g, u);
  return {std::move(m), std::move(stress), std::move(u)};
}

double largest_magnitude(const std::vector<double>& v, int stride, int offset) {
  double m = 0;
  for (std::size_t i = offset; i < v.size(); i += stride) m = std::max(m, std::abs(v[i]));
  return m;
}

}  // namespace

TEST(Turning, TurningIsTheDefaultPathLaw) {
  EXPECT_EQ(Coefficients{}.directional.paths, Paths::Turning);
  EXPECT_STREQ(find_coefficient("paths")->choice_name(double(Paths::Mirror)), "mirror");
}

TEST(Turning, FittedSlopeIsExactOnAQuadratic) {
  // A least-squares quadratic reproduces a quadratic: slope 3 + 2 x 0.5 j at every entry, ends included.
  std::vector<double> f(9), slope(9);
  for (int j = 0; j < 9; ++j) f[j] = 1 + 3 * j + 0.5 * j * j;
  fitted_slope(f.data(), 1, 9, 2.5, slope.data());
  for (int j = 0; j < 9; ++j) EXPECT_NEAR(slope[j], 3 + j, 1e-10) << j;
}

TEST(Turning, FittedSlopeIsExactOnALongQuadratic) {
  // A line longer than two reaches (window 2.5: 10 entries each way) takes the interior's and the
  // ends' weights computed once: still 3 + j at every entry, both ends included.
  std::vector<double> f(60), slope(60);
  for (int j = 0; j < 60; ++j) f[j] = 1 + 3 * j + 0.5 * j * j;
  fitted_slope(f.data(), 1, 60, 2.5, slope.data());
  for (int j = 0; j < 60; ++j) EXPECT_NEAR(slope[j], 3 + j, 1e-9) << j;
  // Strided, as the transfer's per-agent fields are read: the same slopes.
  std::vector<double> g(120, -7.0), strided(120, 0.0);
  for (int j = 0; j < 60; ++j) g[2 * j + 1] = f[j];
  fitted_slope(g.data() + 1, 2, 60, 2.5, strided.data() + 1);
  for (int j = 0; j < 60; ++j) EXPECT_EQ(strided[2 * j + 1], slope[j]) << j;
}

TEST(Turning, AUniformSigmaYGivesNoShearAndNoTie) {
  // No shear flux and no balance: equilibrium needs no tau and no sigma_x (no rigid face: no layer).
  const Grid g = steel_plate(8, 6, false);
  std::vector<double> normal(g.count() * 2, 0.0);
  for (std::size_t c = 0; c < g.count(); ++c) normal[2 * c + 1] = -1000.0;
  const std::vector<double> no_shear(g.count(), 0.0), no_balance(2 * (8 + 6 + 1), 0.0);
  const auto s = directional_stress_components(g, normal, no_shear, no_balance, DirectionalCoefficients{}, 0.3,
                                         {{g.index(4, 5, 0), direction(1, false), 1.0}});
  for (std::size_t c = 0; c < g.count(); ++c) {
    EXPECT_EQ(s.shear[c], 0.0);
    EXPECT_EQ(s.sigma[2 * c], 0.0);
    EXPECT_EQ(s.sigma[2 * c + 1], -1000.0);
    EXPECT_NEAR(s.von_mises[c], 1000.0, 1e-9);  // uniaxial
  }
}

TEST(Turning, TheTieIsHorizontalEquilibriumZeroAtTheFreeSides) {
  // tau = c y (x - W / 2): d tau / dy = c (x - W / 2), so sigma_x(x) = -int_0^x c (x' - W/2) dx'
  // = c (W x / 2 - x^2 / 2): zero at both free sides (x = 0 and W, the row's force balanced), an
  // agent the mean of its faces. The fit reproduces a linear tau exactly.
  const int nx = 10, ny = 7;
  const Grid g = steel_plate(nx, ny, false);
  const double h = 5e-3, W = nx * h, c = 3e7;
  std::vector<double> tau(g.count(), 0.0), no_balance(2 * (nx + ny + 1), 0.0), normal(g.count() * 2, 0.0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) tau[g.index(i, j, 0)] = c * (j + 0.5) * h * ((i + 0.5) * h - W / 2);
  const auto s = directional_stress_components(g, normal, tau, no_balance, DirectionalCoefficients{}, 0.3,
                                         {{g.index(4, ny - 1, 0), direction(1, false), 1.0}});
  auto at_face = [&](double x) { return c * (W * x / 2 - x * x / 2); };
  for (int j = 0; j < ny; ++j) {
    double row_force = 0;
    for (int i = 0; i < nx; ++i) {
      const std::size_t cell = g.index(i, j, 0);
      EXPECT_NEAR(s.shear[cell], c * (j + 0.5) * h * ((i + 0.5) * h - W / 2), 1e-6) << i << "," << j;
      EXPECT_NEAR(s.sigma[2 * cell], 0.5 * (at_face(i * h) + at_face((i + 1) * h)), 1e-6) << i << "," << j;
      row_force += s.sigma[2 * cell];
    }
    // The free sides' agents hold half their inner face's stress (the side face is 0).
    EXPECT_NEAR(s.sigma[2 * g.index(0, j, 0)], 0.5 * at_face(h), 1e-6);
    EXPECT_NEAR(s.sigma[2 * g.index(nx - 1, j, 0)], 0.5 * at_face((nx - 1) * h), 1e-6);
  }
}

TEST(Turning, In3DEachLayerAcrossTheMarchIsSolvedForItsInPlaneStresses) {
  // 3D, loads along y, no rigid face (no layer on a face): each layer j across y is a LayerSolver
  // problem with sigma_y as its normal stress and d tau_yz / dy as its body force along z. With
  // tau_yz = c y f(x, z) the centred derivative is c f exactly, and sigma_y = q(x, z), so every
  // layer is the same problem: sigma_x, sigma_z and tau_xz are one LayerSolver answer, the packets'
  // tau_xz replaced. A second load along x shares tau_xz's pair: its march's tau_xz is kept and
  // the layers' added (its own layers carry nothing here: no sigma_x, no tau along x).
  const int nx = 8, ny = 5, nz = 6;
  const double h = 5e-3, W = nx * h, D = nz * h, c = 3e7, packets = 123.0;
  Grid g = Grid::box(3, {nx, ny, nz}, Eigen::Vector3d(h, h, h));
  std::vector<double> shear(g.count() * 3, 0.0), normal(g.count() * 3, 0.0), no_balance(2 * (nx + ny + nz), 0.0);
  LayerBox box{nx, nz, h, h, std::vector<char>(nx * nz, 1)};
  LayerFields layer{std::vector<double>(nx * nz), std::vector<double>(nx * nz), std::vector<double>(nx * nz), {}, {}, {}};
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * h, z = (k + 0.5) * h, f = (z - D / 2) * (1 + x / W), q = -1e4 * (1 + x * z / (W * D));
      layer.normal[i + nx * k] = q;
      layer.body1[i + nx * k] = c * f;
      for (int j = 0; j < ny; ++j) {
        const std::size_t cell = g.index(i, j, k);
        normal[3 * cell + 1] = q;
        shear[3 * cell + 1] = c * (j + 0.5) * h * f;  // tau_yz
        shear[3 * cell + 2] = packets;                // tau_xz
      }
    }
  LayerSolver(0.3).solve(box, layer);
  const std::vector<EntryLoad> down{{g.index(3, ny - 1, 2), direction(1, false), 1.0}};
  const std::vector<EntryLoad> also_along_x{down[0], {g.index(0, 2, 2), direction(0, true), 1.0}};
  const auto s = directional_stress_components(g, normal, shear, no_balance, DirectionalCoefficients{}, 0.3, down);
  const auto both = directional_stress_components(g, normal, shear, no_balance, DirectionalCoefficients{}, 0.3, also_along_x);
  double largest = 0;
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t cell = g.index(i, j, k), at = std::size_t(i + nx * k);
        EXPECT_NEAR(s.sigma[3 * cell], layer.sigma0[at], 1e-9 * std::abs(layer.sigma0[at]) + 1e-9) << i << j << k;
        EXPECT_NEAR(s.sigma[3 * cell + 2], layer.sigma1[at], 1e-9 * std::abs(layer.sigma1[at]) + 1e-9) << i << j << k;
        EXPECT_NEAR(s.shear[3 * cell + 2], layer.tau01[at], 1e-9 * std::abs(layer.tau01[at]) + 1e-9) << i << j << k;
        EXPECT_NEAR(both.shear[3 * cell + 2], packets + layer.tau01[at], 1e-9 * std::abs(layer.tau01[at]) + 1e-9);
        EXPECT_EQ(s.sigma[3 * cell + 1], normal[3 * cell + 1]);  // sigma_y: the march's
        largest = std::max(largest, std::abs(layer.tau01[at]));
      }
  EXPECT_GT(largest, 100.0);  // the layers carry something
}

TEST(Turning, EveryRowCarriesTheLoadAndTheBaseReturnsIt) {
  // A load off centre on a plate: every row's agents pass on exactly the load (the deposit is
  // normalised over the row and the moment balance adds nothing net), and the base returns it.
  const Grid g = steel_plate(24, 18);
  Coefficients k;
  k.gamma = 0;
  const double load = 2.0;
  const auto f = solve(g, k, {{g.index(6, 17, 0), direction(1, false), load}});
  const auto& d = f.model.diagnostics();
  for (int j = 0; j < 18; ++j) {
    double through = 0;
    for (int i = 0; i < 24; ++i) through += face(f.model, i, j, kPlusY);
    EXPECT_NEAR(through, load, 1e-13 * load) << "row " << j;
  }
  EXPECT_EQ(d.applied, load);
  EXPECT_NEAR(d.rigid_reaction, load, 1e-13 * load);
  EXPECT_EQ(d.passed_out, 0.0);
  EXPECT_EQ(d.lost, 0.0);
  // No packet reaches a free side mirrored: the free sides carry no sigma_x face force.
  for (int j = 0; j < 18; ++j) EXPECT_EQ(face(f.model, 0, j, kMinusX), 0.0);
}

TEST(Turning, AHoleIsGoneRoundNotPassedOut) {
  // A 6 x 4-agent hole under a centred load: the paths over it go round by the nearer side, so
  // the base returns the whole load, every row passes it on, the hole's faces carry nothing, and
  // the fields stay symmetric about the centre line.
  const int nx = 24, ny = 18;
  Grid g = steel_plate(nx, ny);
  for (int j = 6; j < 10; ++j)
    for (int i = 9; i < 15; ++i) g.make_air(g.index(i, j, 0));
  Coefficients k;
  const double load = 2.0;
  const auto f = solve(g, k, {{g.index(11, ny - 1, 0), direction(1, false), load / 2}, {g.index(12, ny - 1, 0), direction(1, false), load / 2}});
  const auto& d = f.model.diagnostics();
  EXPECT_NEAR(d.rigid_reaction, load, 1e-13 * load);
  EXPECT_EQ(d.passed_out, 0.0);
  for (int j = 0; j < ny; ++j) {
    double through = 0;
    for (int i = 0; i < nx; ++i)
      if (!g.is_air(g.index(i, j, 0))) through += face(f.model, i, j, kPlusY);
    EXPECT_NEAR(through, load, 1e-13 * load) << "row " << j;
  }
  for (int i = 9; i < 15; ++i) EXPECT_EQ(face(f.model, i, 10, kMinusY), 0.0) << i;  // the hole's roof
  const double sy_max = largest_magnitude(f.stress.sigma, 2, 1), tau_max = largest_magnitude(f.stress.shear, 1, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0), m = g.index(nx - 1 - i, j, 0);
      EXPECT_NEAR(f.stress.sigma[2 * c + 1], f.stress.sigma[2 * m + 1], 1e-9 * sy_max) << i << "," << j;
      EXPECT_NEAR(f.stress.shear[c], -f.stress.shear[m], 1e-9 * tau_max) << i << "," << j;
    }
  // Beside the hole the two columns of agents carry the load round it: more than the same
  // agents of the plate without the hole.
  const auto whole = solve(steel_plate(nx, ny), k, {{g.index(11, ny - 1, 0), direction(1, false), load / 2}, {g.index(12, ny - 1, 0), direction(1, false), load / 2}});
  EXPECT_LT(f.stress.sigma[2 * g.index(8, 8, 0) + 1], 1.2 * whole.stress.sigma[2 * g.index(8, 8, 0) + 1]);
}

TEST(Turning, KirschsShearClosedForms) {
  // On the hole's rim sigma_rr = tau_rtheta = 0 and sigma_thetatheta = s (1 - 2 cos 2 theta): at
  // 45 degrees tau_xy = -s / 2. None on the axes; far away the hole's shear fades as (a / r)^2.
  const double a = 0.01, s = 1000.0, r45 = a / std::sqrt(2.0);
  EXPECT_NEAR(kirsch_shear(r45, r45, a, s), -0.5 * s, 1e-12 * s);
  EXPECT_NEAR(kirsch_shear(-r45, r45, a, s), 0.5 * s, 1e-12 * s);
  EXPECT_NEAR(kirsch_shear(0.5 * r45, 0.5 * r45, a, s), -0.5 * s, 1e-12 * s);  // inside: on the rim
  EXPECT_EQ(kirsch_shear(0.03, 0.0, a, s), 0.0);
  EXPECT_NEAR(kirsch_shear(0.0, 0.03, a, s), 0.0, 1e-12 * s);
  EXPECT_EQ(kirsch_shear(0.0, 0.0, a, s), 0.0);
  // At 45 degrees cos 2 theta = 0: tau = (sigma_rr - sigma_thetatheta) / 2 = -s (a / r)^2 / 2.
  for (const double r : {2 * a, 5 * a}) {
    const double q2 = a * a / (r * r), x = r / std::sqrt(2.0);
    EXPECT_NEAR(kirsch_shear(x, x, a, s), -0.5 * s * q2, 1e-12 * s) << r;
  }
  // Linear in s, odd in either offset.
  EXPECT_NEAR(kirsch_shear(0.013, 0.021, a, -2 * s), -2 * kirsch_shear(0.013, 0.021, a, s), 1e-12 * s);
  EXPECT_NEAR(kirsch_shear(-0.013, 0.021, a, s), -kirsch_shear(0.013, 0.021, a, s), 1e-12 * s);
}

namespace {

/// The stress components of a plate with no shear flux and no balance (so no tie): what is left
/// across the march is the bonded base's layer alone. sigma_y everywhere = p(x) of the column.
StressComponents layer_only(const Grid& g, int nx, int ny, const std::function<double(double)>& p) {
  std::vector<double> normal(g.count() * 2, 0.0);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (!g.is_air(c)) normal[2 * c + 1] = p(g.centre(c)[0]);
  const std::vector<double> no_shear(g.count(), 0.0), no_balance(2 * (nx + ny + 1), 0.0);
  return directional_stress_components(g, normal, no_shear, no_balance, DirectionalCoefficients{}, 0.3,
                                 {{g.index(nx / 2, ny - 1, 0), direction(1, false), 1.0}});
}

}  // namespace

TEST(Turning, TheBasesLayerIsTheHalfPlanesAnswerToItsRestraint) {
  // A base pressure p = P1 sin(k1 x) + P3 sin(3 k1 x), k1 = pi / W (sampled at the agents'
  // centres: exactly two sine modes of the run): the bonded base holds sigma_x = nu p on it, and
  // the layer is Airy's phi = B y exp(-k y) sin(k x) per mode: sigma_x = nu P (1 - k y / 2)
  // exp(-k y) sin(k x), tau_xy = nu P / 2 (1 - k y) exp(-k y) cos(k x) (zero normal stress on the
  // face). The plate is tall (6 W) so the shear scanned down from its top starts from about 0.
  const int nx = 24, ny = 144;
  const Grid g = steel_plate(nx, ny);
  const double h = 5e-3, W = nx * h, k1 = M_PI / W, P1 = -3000, P3 = 800, nu = 0.3;
  const auto s = layer_only(g, nx, ny, [&](double x) { return P1 * std::sin(k1 * x) + P3 * std::sin(3 * k1 * x); });
  double largest_tau_error = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0);
      const double x = (i + 0.5) * h, y = (j + 0.5) * h;
      double sx = 0, tau = 0;
      for (const auto& [k, P] : {std::pair{k1, P1}, std::pair{3 * k1, P3}}) {
        sx += nu * P * (1 - 0.5 * k * y) * std::exp(-k * y) * std::sin(k * x);
        tau += 0.5 * nu * P * (1 - k * y) * std::exp(-k * y) * std::cos(k * x);
      }
      ASSERT_NEAR(s.sigma[2 * c], sx, 1e-12 * std::abs(nu * P1)) << i << "," << j;
      EXPECT_EQ(s.sigma[2 * c + 1], P1 * std::sin(k1 * x) + P3 * std::sin(3 * k1 * x));  // sigma_y: the march's
      largest_tau_error = std::max(largest_tau_error, std::abs(s.shear[c] - tau));
    }
  // The shear by horizontal equilibrium (central differences across, midpoints up): second order.
  EXPECT_LT(largest_tau_error, 0.02 * 0.5 * nu * std::abs(P1));
  EXPECT_GT(largest_tau_error, 0.0);
}

TEST(Turning, TheLocalLayerIn3DIsItsClosedFormOnAUniformPressure) {
  // 3D, a 6 x 4 x 6 block of 4 mm agents on a rigid base, sigma_y = p = -1000 Pa at every agent, no
  // shear: sigma_x and sigma_z are the local layer alone (the layers across y take a uniform
  // sigma_y unstressed), nu / (1 - nu) p max(0, 1 - y / ell)
  // (1 - exp(-d_side / y)), ell = 0.25 x the pressure's width sqrt(12 variance) = 0.25 h sqrt(35)
  // (six equal agents: variance h^2 (36 - 1) / 12) = 5.916 mm, so only the bottom layer (y = 2 mm)
  // has one. By hand at the corner agent (d_side = 2 mm): 3 / 7 x -1000 x (1 - 2 / 5.916) x (1 -
  // exp(-1)) = -179.325 Pa; at d_side = 6 and 10 mm -269.564 and -281.776 Pa. Its shear by
  // horizontal equilibrium from the top: 0 above, h / 2 d sigma_x / dx in the bottom layer.
  const int n = 6, ny = 4;
  const double h = 4e-3, p = -1000;
  Grid g = Grid::box(3, {n, ny, n}, Eigen::Vector3d(h, h, h));
  g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  std::vector<double> normal(g.count() * 3, 0.0), no_shear(g.count() * 3, 0.0), no_balance(2 * (n + ny + n), 0.0);
  for (std::size_t c = 0; c < g.count(); ++c) normal[3 * c + 1] = p;
  const auto s = directional_stress_components(g, normal, no_shear, no_balance, DirectionalCoefficients{}, 0.3,
                                               {{g.index(n / 2, ny - 1, n / 2), direction(1, false), 1.0}});
  const double by_hand[3] = {-179.32491724732648, -269.56385605943717, -281.77636840254553};
  auto layer = [&](int i, int j) { return j > 0 ? 0.0 : by_hand[std::min(i, n - 1 - i)]; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = g.index(i, j, k);
        // (the layers' solve leaves a uniform sigma_y unstressed, to 1e-10 of it: its shift)
        EXPECT_NEAR(s.sigma[3 * c], layer(i, j), 1e-7 * std::abs(p)) << i << "," << j << "," << k;
        EXPECT_NEAR(s.sigma[3 * c + 2], layer(k, j), 1e-7 * std::abs(p)) << i << "," << j << "," << k;
        EXPECT_EQ(s.sigma[3 * c + 1], p);  // sigma_y: the march's
        const int lo = std::max(0, i - 1), hi = std::min(n - 1, i + 1);
        const double slope = (layer(hi, j) - layer(lo, j)) / ((hi - lo) * h);
        EXPECT_NEAR(s.shear[3 * c], 0.5 * h * slope, 1e-9) << i << "," << j << "," << k;  // tau_xy
        EXPECT_NEAR(s.shear[3 * c + 2], 0.0, 1e-7 * std::abs(p));  // tau_xz: the layers' (none)
      }
}

TEST(Turning, AWideningDepositCarriesItsShearIn3D) {
  // 3D: a row's Gaussian of variance diffusion_length x depth (L d) moves its mass sideways at
  // (x - centre) / (2 d), so its shear's first moment about the load line, sum of tau_xy A (x - x0)
  // over a row, is F L / 2 at every depth (F sigma^2 / (2 d)); the path's own shear does not depend
  // on L. Two diffusion lengths differ by F (L1 - L2) / 2 in that moment, times c = (d / top + d /
  // bottom) / 2 (an agent takes the mean of its faces' 1 / (2 depth)): 1 N, L 2 and 1 mm: 0.5 N mm.
  const int n = 61, ny = 8;
  const double h = 1e-3, F = 1.0;
  Grid g = Grid::box(3, {n, ny, n}, Eigen::Vector3d(h, h, h));
  g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  const std::vector<EntryLoad> loads{{g.index(n / 2, ny - 1, n / 2), direction(1, false), F}};
  auto moments = [&](double diffusion) {
    Coefficients k;
    k.gamma = 0;
    k.directional.diffusion_length = diffusion;
    LoadTransfer m(g, kSteel, k, RuleSet::Directional);
    m.solve(loads);
    std::vector<double> moment(ny, 0.0);
    for (int j = 0; j < ny; ++j)
      for (int kz = 0; kz < n; ++kz)
        for (int i = 0; i < n; ++i)
          moment[j] += m.shear_stress()[3 * g.index(i, j, kz)] * h * h * (i - n / 2) * h;
    return moment;
  };
  const auto wide = moments(2e-3), narrow = moments(1e-3);
  for (int j = 1; j < ny - 1; ++j) {  // depth index ny - 1 - j below the loaded face
    const double top = ny - 1 - j, bottom = top + 1, centre = top + 0.5;
    const double expected = F * (2e-3 - 1e-3) / 2 * 0.5 * (centre / top + centre / bottom);
    EXPECT_NEAR(std::abs(wide[j] - narrow[j]), expected, 0.02 * expected) << "row " << j;
  }
}

TEST(Turning, EachRunOnTheBaseHasItsOwnFreeEnds) {
  // The base split by a notch of air in its lowest rows: each run on it is a half-plane of its own
  // width with free ends. A pressure on the left run only leaves the right run's columns without
  // layer, and the left run's is that of a plate as wide as it.
  const int nx = 20, ny = 30, left = 8;
  Grid g = steel_plate(nx, ny);
  for (int j = 0; j < 3; ++j)
    for (int i = left; i < left + 4; ++i) g.make_air(g.index(i, j, 0));
  const double h = 5e-3;
  const auto p = [&](double x) { return x < left * h ? -1000.0 - 2e5 * x : 0.0; };
  const auto s = layer_only(g, nx, ny, p);
  const Grid alone = steel_plate(left, ny);
  const auto a = layer_only(alone, left, ny, p);
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < left; ++i)
      EXPECT_NEAR(s.sigma[2 * g.index(i, j, 0)], a.sigma[2 * alone.index(i, j, 0)], 1e-12 * 300) << i << "," << j;
    for (int i = left + 4; i < nx; ++i) EXPECT_EQ(s.sigma[2 * g.index(i, j, 0)], 0.0) << i << "," << j;
  }
  EXPECT_LT(s.sigma[2 * g.index(3, 0, 0)], -0.5 * 0.3 * 1000);  // a layer there: the compression of nu p
}

TEST(Turning, AHoleIsTheEnclosedAirOnlyAndItsShearIsKirschs) {
  // A 4 x 4-agent hole at the centre of a 40 x 40 plate and a notch from the left side: one hole,
  // of 16 agents' area at the plate's centre. Under a uniform sigma_y its shear is Kirsch's for the
  // circle of its area, the remote stress the row's force over the row's extent (36 of 40 agents).
  const int nx = 40, ny = 40;
  Grid g = steel_plate(nx, ny);
  const double h = 5e-3;
  for (int j = 18; j < 22; ++j)
    for (int i = 18; i < 22; ++i) g.make_air(g.index(i, j, 0));
  for (int i = 0; i < 4; ++i) g.make_air(g.index(i, 30, 0));
  const auto holes = enclosed_holes(g);
  ASSERT_EQ(holes.size(), 1u);
  EXPECT_NEAR(holes[0].area, 16 * h * h, 1e-12 * h * h);
  EXPECT_NEAR(holes[0].centre[0], 20 * h, 1e-12);
  EXPECT_NEAR(holes[0].centre[1], 20 * h, 1e-12);
  const double sigma = -1000.0;
  std::vector<double> normal(2 * g.count(), 0.0);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (!g.is_air(c)) normal[2 * c + 1] = sigma;
  const auto tau = hole_shear(g, 1, normal);
  const double radius = std::sqrt(16 * h * h / std::acos(-1.0)), remote = sigma * 36 / 40;
  for (const auto& [i, j] : {std::pair{22, 22}, std::pair{17, 23}, std::pair{25, 19}, std::pair{0, 0}}) {
    const Eigen::Vector3d x = g.centre(g.index(i, j, 0));
    EXPECT_NEAR(tau[g.index(i, j, 0)], kirsch_shear(x[1] - 20 * h, x[0] - 20 * h, radius, remote), 1e-9) << i << "," << j;
  }
  EXPECT_GT(tau[g.index(22, 22, 0)], 0.0);  // compression: the opposite of a pull's -s q^2 / 2 at 45 degrees
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0), mx = g.index(nx - 1 - i, j, 0), my = g.index(i, ny - 1 - j, 0);
      if (g.is_air(c) || g.is_air(mx) || g.is_air(my)) continue;  // the hole, the notch and their mirrors
      EXPECT_NEAR(tau[c], -tau[mx], 1e-9) << i << "," << j;
      EXPECT_NEAR(tau[c], -tau[my], 1e-9) << i << "," << j;
    }
  // Beyond 10 radii of the hole nothing is added (Kirsch's disturbance there is under 1.5 % of the
  // remote stress): a plate twice as wide, the same hole, an agent 40 agents to its right.
  Grid wide = steel_plate(2 * nx, ny);
  for (int j = 18; j < 22; ++j)
    for (int i = 18; i < 22; ++i) wide.make_air(wide.index(i, j, 0));
  std::vector<double> wide_normal(2 * wide.count(), 0.0);
  for (std::size_t c = 0; c < wide.count(); ++c)
    if (!wide.is_air(c)) wide_normal[2 * c + 1] = sigma;
  const auto wide_tau = hole_shear(wide, 1, wide_normal);
  const double wide_remote = sigma * 76 / 80;
  const Eigen::Vector3d far = wide.centre(wide.index(60, 22, 0)), near = wide.centre(wide.index(22, 22, 0));
  EXPECT_EQ(wide_tau[wide.index(60, 22, 0)], 0.0);
  EXPECT_LT(std::abs(kirsch_shear(far[1] - 20 * h, far[0] - 20 * h, radius, wide_remote)), 0.015 * std::abs(wide_remote));
  EXPECT_NEAR(wide_tau[wide.index(22, 22, 0)], kirsch_shear(near[1] - 20 * h, near[0] - 20 * h, radius, wide_remote), 1e-9);
  // Without a hole nothing is added (the notch alone is not one).
  Grid notched = steel_plate(nx, ny);
  for (int i = 0; i < 4; ++i) notched.make_air(notched.index(i, 30, 0));
  EXPECT_TRUE(enclosed_holes(notched).empty());
  for (double t : hole_shear(notched, 1, normal)) EXPECT_EQ(t, 0.0);
  // A hole wider than its walls (30 x 30 agents in 40 x 40: 5 agents each side, radius 16.9) is a
  // ring's inside, not Kirsch's hole: nothing added.
  Grid ring = steel_plate(nx, ny);
  for (int j = 5; j < 35; ++j)
    for (int i = 5; i < 35; ++i) ring.make_air(ring.index(i, j, 0));
  ASSERT_EQ(enclosed_holes(ring).size(), 1u);
  for (double t : hole_shear(ring, 1, normal)) EXPECT_EQ(t, 0.0);
}

TEST(Turning, ACentredLoadGivesSymmetricSigmaXAndAntisymmetricShearAndUx) {
  const int nx = 20, ny = 16;
  const Grid g = steel_plate(nx, ny);
  Coefficients k;
  const auto f = solve(g, k, {{g.index(9, ny - 1, 0), direction(1, false), 1.0}, {g.index(10, ny - 1, 0), direction(1, false), 1.0}});
  const double sx_max = largest_magnitude(f.stress.sigma, 2, 0), tau_max = largest_magnitude(f.stress.shear, 1, 0);
  const double ux_max = largest_magnitude(f.u, 2, 0), uy_max = largest_magnitude(f.u, 2, 1);
  ASSERT_GT(sx_max, 0);
  ASSERT_GT(tau_max, 0);
  ASSERT_GT(ux_max, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0), m = g.index(nx - 1 - i, j, 0);
      EXPECT_NEAR(f.stress.sigma[2 * c], f.stress.sigma[2 * m], 1e-9 * sx_max) << i << "," << j;
      EXPECT_NEAR(f.stress.sigma[2 * c + 1], f.stress.sigma[2 * m + 1], 1e-9 * largest_magnitude(f.stress.sigma, 2, 1));
      EXPECT_NEAR(f.stress.shear[c], -f.stress.shear[m], 1e-9 * tau_max) << i << "," << j;
    }
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) {
      const std::size_t n = g.node_index(i, j, 0), m = g.node_index(nx - i, j, 0);
      EXPECT_NEAR(f.u[2 * n], -f.u[2 * m], 1e-9 * ux_max) << i << "," << j;
      EXPECT_NEAR(f.u[2 * n + 1], f.u[2 * m + 1], 1e-9 * uy_max) << i << "," << j;
    }
  // Under the load the turning packets pull the load line apart: tension at mid-depth, as FEM.
  EXPECT_GT(f.stress.sigma[2 * g.index(10, ny / 2, 0)], 0.0);
  // The plate bulges: the right side moves out (+x), the left one in mirror, above the base.
  EXPECT_GT(f.u[2 * g.node_index(nx, ny / 2, 0)], 0.0);
}

TEST(Turning, TheRigidFaceHoldsZeroDisplacement) {
  const Grid g = steel_plate(16, 12);
  Coefficients k;
  for (const Paths paths : {Paths::Turning, Paths::Mirror}) {
    k.directional.paths = paths;
    const auto f = solve(g, k, {{g.index(5, 11, 0), direction(1, false), 2.0}});
    for (int i = 0; i <= 16; ++i) {
      EXPECT_EQ(f.u[2 * g.node_index(i, 0, 0)], 0.0) << i;
      EXPECT_EQ(f.u[2 * g.node_index(i, 0, 0) + 1], 0.0) << i;
    }
    EXPECT_LT(f.u[2 * g.node_index(5, 12, 0) + 1], 0.0);  // the loaded face moves down
  }
}

TEST(Turning, TheMirrorPathsCarryShearToo) {
  // The mirror's packets carry their shear flux as well (tau = F s / A per packet): a centred
  // load gives an antisymmetric tau, and a free side none across it only in the mean.
  const int nx = 12, ny = 10;
  const Grid g = steel_plate(nx, ny);
  Coefficients k;
  k.directional.paths = Paths::Mirror;
  const auto f = solve(g, k, {{g.index(5, ny - 1, 0), direction(1, false), 1.0}, {g.index(6, ny - 1, 0), direction(1, false), 1.0}});
  const double tau_max = largest_magnitude(f.stress.shear, 1, 0);
  ASSERT_GT(tau_max, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      EXPECT_NEAR(f.stress.shear[g.index(i, j, 0)], -f.stress.shear[g.index(nx - 1 - i, j, 0)], 1e-9 * tau_max);
}

TEST(Turning, ABlockCentredLoadIsBalancedAndSymmetricInBothLateralAxes) {
  // 3D: a square block, the load on the centre 2 x 2 agents of its top. Each layer passes on the
  // load, the base returns it; sigma_x and sigma_z trade places under x <-> z; tau_xy is odd in x
  // and even in z, tau_yz odd in z.
  const int n = 10, ny = 8;
  Grid g = Grid::box(3, {n, ny, n}, Eigen::Vector3d(4e-3, 4e-3, 4e-3));
  g.set_boundary(g.box_side(kMinusY), Boundary::Rigid);
  Coefficients k;
  k.gamma = 0;
  k.directional.directions = 8;
  std::vector<EntryLoad> loads;
  for (int i : {4, 5})
    for (int kz : {4, 5}) loads.push_back({g.index(i, ny - 1, kz), direction(1, false), 0.5});
  LoadTransfer m(g, kSteel, k, RuleSet::Directional);
  m.solve(loads);
  const auto& d = m.diagnostics();
  EXPECT_NEAR(d.rigid_reaction, 2.0, 1e-13);
  EXPECT_EQ(d.passed_out, 0.0);
  for (int j = 0; j < ny; ++j) {
    double through = 0;
    for (int kz = 0; kz < n; ++kz)
      for (int i = 0; i < n; ++i) through += m.face_forces()[g.index(i, j, kz) * 6 + kPlusY];
    EXPECT_NEAR(through, 2.0, 1e-13) << "layer " << j;
  }
  const auto normal = agent_stresses(g, m.face_forces());
  const auto s = directional_stress_components(g, normal, m.shear_stress(), m.balance_slopes(), k.directional, kSteel.poisson, loads);
  const double sx_max = largest_magnitude(s.sigma, 3, 0), txy_max = largest_magnitude(s.shear, 3, 0);
  const double tyz_max = largest_magnitude(s.shear, 3, 1);
  ASSERT_GT(sx_max, 0);
  ASSERT_GT(txy_max, 0);
  EXPECT_NEAR(tyz_max, txy_max, 1e-9 * txy_max);
  for (int kz = 0; kz < n; ++kz)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < n; ++i) {
        const std::size_t c = g.index(i, j, kz), swap = g.index(kz, j, i), mx = g.index(n - 1 - i, j, kz);
        const std::size_t mz = g.index(i, j, n - 1 - kz);
        EXPECT_NEAR(s.sigma[3 * c], s.sigma[3 * swap + 2], 1e-9 * sx_max) << i << "," << j << "," << kz;
        EXPECT_NEAR(s.sigma[3 * c], s.sigma[3 * mx], 1e-9 * sx_max);
        EXPECT_NEAR(s.shear[3 * c], -s.shear[3 * mx], 1e-9 * txy_max);
        EXPECT_NEAR(s.shear[3 * c], s.shear[3 * mz], 1e-9 * txy_max);
        EXPECT_NEAR(s.shear[3 * c + 1], -s.shear[3 * mz + 1], 1e-9 * txy_max);
        // tau_xz is odd in x and in z and the same under x <-> z
        EXPECT_NEAR(s.shear[3 * c + 2], -s.shear[3 * mx + 2], 1e-9 * txy_max);
        EXPECT_NEAR(s.shear[3 * c + 2], -s.shear[3 * mz + 2], 1e-9 * txy_max);
        EXPECT_NEAR(s.shear[3 * c + 2], s.shear[3 * swap + 2], 1e-9 * txy_max);
      }
  // A packet of force F with slopes (s_x, s_z) is the ray's stress -F n n^T / A: tau_xy = F s_x / A,
  // tau_yz = F s_z / A, tau_xz = -F s_x s_z / A. A row's packets are the product of one
  // distribution per axis, so at every agent the transfer's shears and the force through it
  // (sigma = F / A) keep tau_xz sigma = -tau_xy tau_yz.
  const auto& flux = m.shear_stress();
  const double area = g.face_area(1);
  double txz_max = 0;
  for (std::size_t c = 0; c < g.count(); ++c) {
    const double sigma = m.face_forces()[c * 6 + kPlusY] / area;
    EXPECT_NEAR(flux[3 * c + 2] * sigma, -flux[3 * c] * flux[3 * c + 1], 1e-9 * txy_max * txy_max) << c;
    txz_max = std::max(txz_max, std::abs(flux[3 * c + 2]));
  }
  EXPECT_GT(txz_max, 0.01 * txy_max);
}

TEST(Turning, TheNearSidesImageSpreadsTheLoadAsBeamStaticsFarBelow) {
  // near_side = image (docs/agent-model.md, "Loads near a side"): a load 3 agents from the side of
  // a square plate reaches the base as beam statics' linear pressure, P / W (1 + 12 e (x - W / 2) /
  // W^2), e the load's offset from the middle (FEM's base pressure on the seed plate is that line to
  // a few %). With each half of the fan on its own side's width the near side's half piles up there.
  const int n = 24;
  const Grid g = steel_plate(n, n);
  const double load = 2.0, width = n * 5e-3, x0 = 3.5 * 5e-3;
  auto rms_off_the_line = [&](NearSide near_side) {
    Coefficients k;
    k.gamma = 0;
    k.directional.near_side = near_side;
    const auto f = solve(g, k, {{g.index(3, n - 1, 0), direction(1, false), load}});
    const auto& d = f.model.diagnostics();
    EXPECT_NEAR(d.rigid_reaction, load, 1e-13 * load);  // the load balance stays exact
    EXPECT_EQ(d.passed_out, 0.0);
    for (int j = 0; j < n; ++j) {
      double through = 0;
      for (int i = 0; i < n; ++i) through += face(f.model, i, j, kPlusY);
      EXPECT_NEAR(through, load, 1e-13 * load) << "row " << j;
    }
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      const double x = (i + 0.5) * 5e-3;
      const double line = load / n * (1 + 12 * (x0 - width / 2) * (x - width / 2) / (width * width));
      sum += std::pow(face(f.model, i, 0, kMinusY) - line, 2);
    }
    return std::sqrt(sum / n) / (load / n);  // in units of the mean force per agent
  };
  EXPECT_LT(rms_off_the_line(NearSide::Image), 0.07);  // the numpy prototype: 0.049
  EXPECT_GT(rms_off_the_line(NearSide::Side), 0.3);    // 0.337
}

TEST(Turning, TheNearSidesImageLeavesACentredLoadsForceAndKeepsItsSymmetry) {
  // A load on the middle agent of an odd plate: both sides have the same width, so the image maps
  // the fan as before and no path crosses a side: the force through every face is the same to the
  // bit. Only the shear differs (the Gaussians' images at the sides carry the negated slope), and
  // it stays antisymmetric, sigma_x and sigma_y symmetric.
  const int nx = 21, ny = 16;
  const Grid g = steel_plate(nx, ny);
  Coefficients side, image;
  side.directional.near_side = NearSide::Side;
  image.directional.near_side = NearSide::Image;
  const std::vector<EntryLoad> loads{{g.index(10, ny - 1, 0), direction(1, false), 2.0}};
  const auto a = solve(g, side, loads), b = solve(g, image, loads);
  EXPECT_EQ(a.model.face_forces(), b.model.face_forces());
  EXPECT_NE(a.stress.shear, b.stress.shear);
  const double sx_max = largest_magnitude(b.stress.sigma, 2, 0), tau_max = largest_magnitude(b.stress.shear, 1, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0), m = g.index(nx - 1 - i, j, 0);
      EXPECT_NEAR(b.stress.sigma[2 * c], b.stress.sigma[2 * m], 1e-9 * sx_max) << i << "," << j;
      EXPECT_NEAR(b.stress.shear[c], -b.stress.shear[m], 1e-9 * tau_max) << i << "," << j;
    }
  EXPECT_STREQ(find_coefficient("near_side")->choice_name(double(NearSide::Image)), "image");
}

TEST(Turning, TheBlendMixesTheSideAndImageRulesRowByRow) {
  // near_side = blend (the default; docs/agent-model.md, "Loads near a side"): the row at depth d
  // below the loaded face carries b = exp(-2 d / W) of each direction on its side path and the rest
  // on its image path. Every step is linear in the deposits (the row balance too), so each
  // agent's face forces and packets' shear are b x the side rule's + (1 - b) x the image's of its
  // row, to round-off; every row passes the load on.
  const int n = 24;
  const Grid g = steel_plate(n, n);
  const double load = 2.0;
  const std::vector<EntryLoad> loads{{g.index(3, n - 1, 0), direction(1, false), load}};
  Coefficients side, image, blend;
  side.directional.near_side = NearSide::Side;
  image.directional.near_side = NearSide::Image;
  EXPECT_EQ(blend.directional.near_side, NearSide::Blend);
  EXPECT_STREQ(find_coefficient("near_side")->choice_name(double(NearSide::Blend)), "blend");
  const auto a = solve(g, side, loads), b = solve(g, image, loads), c = solve(g, blend, loads);
  EXPECT_NEAR(c.model.diagnostics().rigid_reaction, load, 1e-13 * load);
  const auto &fa = a.model.face_forces(), &fb = b.model.face_forces(), &fc = c.model.face_forces();
  const auto &ta = a.model.shear_stress(), &tb = b.model.shear_stress(), &tc = c.model.shear_stress();
  const double tau_max = largest_magnitude(tc, 1, 0);
  const std::size_t faces = fa.size() / g.count();
  for (int j = 0; j < n; ++j) {
    const double on_side = std::exp(-2 * (n - 1 - j + 0.5) / n);  // depth and width in agents
    double through = 0;
    for (int i = 0; i < n; ++i) {
      const std::size_t cell = g.index(i, j, 0);
      for (std::size_t k = 0; k < faces; ++k) {
        const std::size_t at = cell * faces + k;
        EXPECT_NEAR(fc[at], on_side * fa[at] + (1 - on_side) * fb[at], 1e-12 * load) << i << "," << j << "," << k;
      }
      EXPECT_NEAR(tc[cell], on_side * ta[cell] + (1 - on_side) * tb[cell], 1e-12 * tau_max) << i << "," << j;
      through += face(c.model, i, j, kPlusY);
    }
    EXPECT_NEAR(through, load, 1e-13 * load) << "row " << j;
  }
  EXPECT_NE(fc, fa);  // (and so the mix is neither rule)
  EXPECT_NE(fc, fb);
}

TEST(Turning, TheBlendKeepsACentredLoadsSymmetry) {
  // A load on the middle agent of an odd plate under the blend: sigma_x and sigma_y symmetric,
  // tau_xy antisymmetric about the load's line.
  const int nx = 21, ny = 16;
  const Grid g = steel_plate(nx, ny);
  const auto f = solve(g, Coefficients{}, {{g.index(10, ny - 1, 0), direction(1, false), 2.0}});
  const double s_max = largest_magnitude(f.stress.sigma, 2, 1), tau_max = largest_magnitude(f.stress.shear, 1, 0);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const std::size_t c = g.index(i, j, 0), m = g.index(nx - 1 - i, j, 0);
      EXPECT_NEAR(f.stress.sigma[2 * c], f.stress.sigma[2 * m], 1e-9 * s_max) << i << "," << j;
      EXPECT_NEAR(f.stress.sigma[2 * c + 1], f.stress.sigma[2 * m + 1], 1e-9 * s_max) << i << "," << j;
      EXPECT_NEAR(f.stress.shear[c], -f.stress.shear[m], 1e-9 * tau_max) << i << "," << j;
    }
}
