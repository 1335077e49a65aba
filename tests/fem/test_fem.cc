// Verification of the deal.II FEM reference (docs/fem-reference.md): manufactured solutions with
// convergence rates, Cook's membrane, the Timoshenko-Goodier cantilever, equilibrium of reactions,
// and bad input. Only the plain-data API is used (no deal.II here).
#include <fem_reference/fem_case.h>
#include <fem_reference/mpi.h>
#include <workbench/error.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "../support/scratch_folder.h"

namespace fs = std::filesystem;
using namespace fem_reference;

namespace {

const std::string kSource = WORKBENCH_SOURCE_DIR;
const double kPi = 3.14159265358979323846;

double rate(double coarse, double fine) { return std::log2(coarse / fine); }

// ------------------------------------------------------------------------------------------------
// Manufactured solution u = a s(x) + B x with s = prod sin(pi x_k): f = -(lambda+mu) H(s) a - mu lap(s) a
// (constant coefficients; 2D plane strain). All boundaries: u prescribed.
// ------------------------------------------------------------------------------------------------

struct Manufactured {
  int dim;
  double E = 1.0, nu = 0.3;
  double a[3] = {0.3, -0.2, 0.25};
  double B[3][3] = {{0.01, 0.02, 0.0}, {-0.01, 0.03, 0.01}, {0.02, 0.0, -0.01}};

  double lambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  double mu() const { return E / (2 * (1 + nu)); }
  // s, grad s, Hessian of s
  void s_derivatives(const double* x, double& s, double* g, double* h) const {
    double sn[3], cs[3];
    for (int k = 0; k < 3; ++k) {
      sn[k] = k < dim ? std::sin(kPi * x[k]) : 1.0;
      cs[k] = k < dim ? kPi * std::cos(kPi * x[k]) : 0.0;
    }
    s = sn[0] * sn[1] * sn[2];
    for (int j = 0; j < dim; ++j) {
      g[j] = cs[j];
      for (int k = 0; k < dim; ++k)
        if (k != j) g[j] *= sn[k];
      for (int l = 0; l < dim; ++l) {
        double v = 1;
        for (int k = 0; k < dim; ++k) {
          if (k == j && k == l) v *= -kPi * kPi * sn[k];
          else if (k == j || k == l) v *= cs[k];
          else v *= sn[k];
        }
        h[j * dim + l] = v;
      }
    }
  }
  FemProblem problem(int cells, int degree) const {
    FemProblem p;
    p.name = "manufactured";
    Box box;
    box.cells = {cells, cells, dim == 3 ? cells : 0};
    p.box = box;
    p.young = E;
    p.poisson = nu;
    p.options.degree = degree;
    p.options.model = Model::PlaneStrain;
    p.options.solver = SolverKind::Amg;
    p.options.tolerance = 1e-12;
    const Manufactured m = *this;
    auto u = [m](const double* x, double* v) {
      double s, g[3], h[9];
      m.s_derivatives(x, s, g, h);
      for (int i = 0; i < m.dim; ++i) {
        v[i] = m.a[i] * s;
        for (int j = 0; j < m.dim; ++j) v[i] += m.B[i][j] * x[j];
      }
    };
    auto grad = [m](const double* x, double* out) {
      double s, g[3], h[9];
      m.s_derivatives(x, s, g, h);
      for (int i = 0; i < m.dim; ++i)
        for (int j = 0; j < m.dim; ++j) out[i * m.dim + j] = m.a[i] * g[j] + m.B[i][j];
    };
    p.body_force_function = [m](const double* x, double* f) {
      double s, g[3], h[9];
      m.s_derivatives(x, s, g, h);
      double lap = 0;
      for (int k = 0; k < m.dim; ++k) lap += h[k * m.dim + k];
      for (int i = 0; i < m.dim; ++i) {
        double ha = 0;
        for (int j = 0; j < m.dim; ++j) ha += h[i * m.dim + j] * m.a[j];
        f[i] = -(m.lambda() + m.mu()) * ha - m.mu() * lap * m.a[i];
      }
    };
    p.exact_displacement = u;
    p.exact_gradient = grad;
    const char* sides[6] = {"x0", "x1", "y0", "y1", "z0", "z1"};
    for (int k = 0; k < 2 * dim; ++k) p.supports.push_back({sides[k], SupportKind::Displacement, u});
    return p;
  }
};

struct Rates {
  double l2, h1, l2_error, h1_error;
};

Rates convergence(int dim, int degree, std::vector<int> cells) {
  Manufactured m{dim};
  std::vector<FemResult> r;
  for (int n : cells) r.push_back(solve_fem(m.problem(n, degree)));
  const auto& a = r[r.size() - 2];
  const auto& b = r.back();
  for (std::size_t i = 0; i < r.size(); ++i)
    std::printf("  %dD Q%d %3d cells/side: %8zu DoFs  L2 %.4e  H1 %.4e\n", dim, degree, cells[i], r[i].n_dofs,
                r[i].l2_error, r[i].h1_error);
  return {rate(a.l2_error, b.l2_error), rate(a.h1_error, b.h1_error), b.l2_error, b.h1_error};
}

TEST(FemManufactured, Q1Plane2DRates) {
  const auto r = convergence(2, 1, {8, 16, 32, 64});
  EXPECT_NEAR(r.l2, 2.0, 0.1);
  EXPECT_NEAR(r.h1, 1.0, 0.05);
}

TEST(FemManufactured, Q2Plane2DRates) {
  const auto r = convergence(2, 2, {4, 8, 16, 32});
  EXPECT_NEAR(r.l2, 3.0, 0.1);
  EXPECT_NEAR(r.h1, 2.0, 0.05);
}

TEST(FemManufactured, Q1Solid3DRates) {
  const auto r = convergence(3, 1, {4, 8, 16});
  EXPECT_NEAR(r.l2, 2.0, 0.15);
  EXPECT_NEAR(r.h1, 1.0, 0.1);
}

TEST(FemManufactured, Q2Solid3DRates) {
  const auto r = convergence(3, 2, {2, 4, 8});
  EXPECT_NEAR(r.l2, 3.0, 0.25);
  EXPECT_NEAR(r.h1, 2.0, 0.15);
}

// ------------------------------------------------------------------------------------------------
// Cook's membrane: plane stress, E = 1, nu = 1/3, clamped left edge, total shear 1 on the right edge.
// The published 23.96 is the vertical displacement of the loaded edge's mid-point (48, 52): the
// literature's standard-Q4 column is reproduced there to four digits (docs/fem-reference.md). The
// top-right corner (48, 60) converges to about 25.19, and in plane strain to what CalculiX,
// Code_Aster and Elmer report for that corner.
// ------------------------------------------------------------------------------------------------

FemResult cook(int n, int degree, Model model = Model::PlaneStress) {
  FemProblem p;
  p.name = "cook";
  p.mesh_file = kSource + "/meshes/cook.geo";
  p.mesh_parameters = {{"n", double(n)}};
  p.young = 1.0;
  p.poisson = 1.0 / 3.0;
  p.thickness = 1.0;
  p.supports.push_back({"left", SupportKind::Clamped, {}});
  p.tractions.push_back({"right", {0.0, 1.0, 0.0}, {}});
  p.options.degree = degree;
  p.options.model = model;
  return solve_fem(p);
}

const std::array<double, 3> kCookMidEdge{48, 52, 0};
const std::array<double, 3> kCookCorner{48, 60, 0};

TEST(FemCook, Q2MidEdgeApproachesPublished2396) {
  // Successive Q2 refinements: v increases with increments shrinking by more than 40 % each (a
  // Cauchy sequence), and approaches 23.96 from below; the clamp balances the load on every mesh.
  std::vector<double> mid, corner;
  for (int n : {4, 8, 16, 32}) {
    const auto r = cook(n, 2);
    mid.push_back(r.displacement_at(kCookMidEdge)[1]);
    corner.push_back(r.displacement_at(kCookCorner)[1]);
    std::printf("  Cook plane stress Q2 n=%2d: v(48,52) = %.4f, v(48,60) = %.4f\n", n, mid.back(),
                corner.back());
    EXPECT_NEAR(r.reactions[0].force[1], -1.0, 1e-8);
  }
  for (const auto& v : {mid, corner}) {
    for (std::size_t i = 1; i < v.size(); ++i) EXPECT_GT(v[i], v[i - 1]);
    for (std::size_t i = 2; i < v.size(); ++i) EXPECT_LT(v[i] - v[i - 1], 0.6 * (v[i - 1] - v[i - 2]));
  }
  EXPECT_LT(mid.back(), 23.965);
  EXPECT_NEAR(mid.back(), 23.96, 0.005);
  // Aitken's extrapolation of the last three values (about 23.971) lies within 0.01 of 23.965.
  const double d1 = mid[2] - mid[1], d2 = mid[3] - mid[2];
  EXPECT_NEAR(mid[3] + d2 * d2 / (d1 - d2), 23.965, 0.01);
  // The corner is 5 % higher; pinned so that a change is noticed (Aitken: about 25.19).
  EXPECT_NEAR(corner.back(), 25.137, 0.01);
}

TEST(FemCook, Q1ReproducesThePublishedQ4Column) {
  // Standard bilinear quadrilaterals on the n x n mesh, mid-point of the loaded edge: the values
  // the benchmark's literature lists for the plain Q4 element, to their last digit.
  const std::vector<std::pair<int, double>> published{
      {2, 11.85}, {4, 18.30}, {8, 22.08}, {16, 23.43}, {64, 23.92}};
  double previous = 0.0;
  for (const auto& [n, v_published] : published) {
    const double v = cook(n, 1).displacement_at(kCookMidEdge)[1];
    std::printf("  Cook Q1 n=%2d: v(48,52) = %.4f (published %.2f)\n", n, v, v_published);
    EXPECT_NEAR(v, v_published, 0.005);
    EXPECT_GT(v, previous);  // Q1 is too stiff and approaches from below
    previous = v;
  }
}

TEST(FemCook, PlaneStrainCornerMatchesThirdPartyCodes) {
  // CoFEA's very fine quadratic meshes (CalculiX 32.27, Code_Aster 32.20, Elmer 32.28 mm for the
  // top-right corner, E = 70, traction 6.25 over the 16 mm edge, i.e. F/E = 100/70) scale to
  // 22.54..22.60.
  const double v = cook(32, 2, Model::PlaneStrain).displacement_at(kCookCorner)[1];
  std::printf("  Cook plane strain Q2 n=32: v(48,60) = %.4f (third-party 22.54..22.60)\n", v);
  EXPECT_NEAR(v, 22.57, 0.04);
}

// ------------------------------------------------------------------------------------------------
// Cantilever L x D (unit thickness, plane stress) under end shear P: Timoshenko & Goodier's solution.
//   u_x = -P y / (6EI) [(6L - 3x) x + (2 + nu)(y^2 - D^2/4)]
//   u_y =  P / (6EI) [3 nu y^2 (L - x) + (4 + 5 nu) D^2 x / 4 + (3L - x) x^2]
//   tip deflection u_y(L, 0) = P L^3 / (3EI) + (4 + 5 nu) P D^2 L / (24 EI)
// ------------------------------------------------------------------------------------------------

struct Cantilever {
  double L = 10, D = 1, E = 1000, nu = 0.3, P = 1;
  double I() const { return D * D * D / 12; }
  double tip() const { return P * L * L * L / (3 * E * I()) + (4 + 5 * nu) * P * D * D * L / (24 * E * I()); }
  /// On a Box (groups x0 root, x1 tip), or with `gmsh` on tests/fem/meshes/strip.geo.
  FemProblem problem(int nx, int ny, int degree, bool exact_ends, bool gmsh = false) const {
    FemProblem p;
    p.name = "cantilever";
    if (gmsh) {
      p.mesh_file = kSource + "/tests/fem/meshes/strip.geo";
      p.mesh_parameters = {{"L", L}, {"D", D}, {"nx", double(nx)}, {"ny", double(ny)}};
    } else {
      Box box;
      box.lo = {0, -D / 2, 0};
      box.hi = {L, D / 2, 0};
      box.cells = {nx, ny, 0};
      p.box = box;
    }
    const std::string root = gmsh ? "root" : "x0", tip = gmsh ? "tip" : "x1";
    p.young = E;
    p.poisson = nu;
    p.options.degree = degree;
    p.options.model = Model::PlaneStress;
    const Cantilever c = *this;
    auto u = [c](const double* x, double* v) {
      const double y = x[1], X = x[0], k = c.P / (6 * c.E * c.I());
      v[0] = -k * y * ((6 * c.L - 3 * X) * X + (2 + c.nu) * (y * y - c.D * c.D / 4));
      v[1] = k * (3 * c.nu * y * y * (c.L - X) + (4 + 5 * c.nu) * c.D * c.D * X / 4 + (3 * c.L - X) * X * X);
    };
    if (exact_ends) {
      p.supports.push_back({root, SupportKind::Displacement, u});
      p.tractions.push_back({tip, {}, [c](const double* x, double* t) {
                               t[0] = 0;
                               t[1] = c.P / (2 * c.I()) * (c.D * c.D / 4 - x[1] * x[1]);
                             }});
      p.exact_displacement = u;
    } else {
      p.supports.push_back({root, SupportKind::Clamped, {}});
      p.tractions.push_back({tip, {0, P, 0}, {}});
    }
    return p;
  }
};

TEST(FemCantilever, TimoshenkoGoodierTipDeflection) {
  Cantilever c;
  const auto r = solve_fem(c.problem(40, 4, 2, true));
  const double v = r.displacement_at({c.L, 0, 0})[1];
  std::printf("  cantilever (exact ends) Q2 40x4: tip %.6f, Timoshenko-Goodier %.6f, L2 error %.3e\n", v, c.tip(),
              r.l2_error);
  EXPECT_NEAR(v / c.tip(), 1.0, 1e-4);
  EXPECT_NEAR(r.reactions[0].force[1], -c.P, 1e-8);
}

TEST(FemCantilever, GmshMeshGivesTheSameTip) {
  Cantilever c;
  for (int degree : {1, 2}) {
    const auto box = solve_fem(c.problem(40, 4, degree, true));
    const auto msh = solve_fem(c.problem(40, 4, degree, true, true));
    const double a = box.displacement_at({c.L, 0, 0})[1], b = msh.displacement_at({c.L, 0, 0})[1];
    std::printf("  cantilever Q%d 40x4: box %.6f, gmsh %.6f\n", degree, a, b);
    EXPECT_NEAR(a, b, 1e-9 * std::abs(a));
  }
}

TEST(FemCantilever, ClampedRootUniformShearWithinOnePercent) {
  // A real clamp and a uniform end shear differ from the exact end conditions only near the ends
  // (Saint-Venant): for L/D = 10 the tip deflection stays within 1 %.
  Cantilever c;
  const auto r = solve_fem(c.problem(80, 8, 2, false));
  const double v = r.displacement_at({c.L, 0, 0})[1];
  std::printf("  cantilever (clamped, uniform shear) Q2 80x8: tip %.6f vs %.6f\n", v, c.tip());
  EXPECT_NEAR(v / c.tip(), 1.0, 0.01);
}

TEST(FemCantilever, ThinStripResidualFloorIsRounding) {
  // L / D = 250: bending of a thin strip. K u cancels terms E |u| about 1e11 times larger than
  // the load, so ||K u - f|| / ||f|| cannot go below about 1e-5 in double precision, however the
  // system is solved. The backward error shows that both solutions solve K u = f to rounding;
  // they then agree to the conditioning (about 1e11 x 1e-16), and with the beam.
  Cantilever c;
  c.L = 500;
  c.D = 2;
  auto p = c.problem(400, 4, 2, false);
  const auto direct = solve_fem(p);
  p.options.solver = SolverKind::Amg;
  p.options.max_iterations = 20000;
  const auto amg = solve_fem(p);
  const double a = direct.displacement_at({c.L, 0, 0})[1], b = amg.displacement_at({c.L, 0, 0})[1];
  std::printf("  thin strip Q2 400x4: direct tip %.8g (residual %.2e, backward error %.2e), "
              "CG+AMG tip %.8g (%d iterations, residual %.2e, backward error %.2e), beam %.8g\n",
              a, direct.residual, direct.backward_error.value_or(-1), b, amg.iterations, amg.residual,
              amg.backward_error.value_or(-1), c.tip());
  for (const auto* r : {&direct, &amg}) {
    EXPECT_GT(r->residual, 1e-8);
    ASSERT_TRUE(r->backward_error.has_value());
    EXPECT_LT(*r->backward_error, 1e-13);
    // The reaction is K u - f on the clamp: the same cancellation (measured 7e-5 and 3e-5).
    EXPECT_NEAR(r->reactions[0].force[1], -c.P, 2e-4 * c.P);
  }
  EXPECT_NEAR(b / a, 1.0, 1e-4);
  EXPECT_NEAR(a / c.tip(), 1.0, 1e-3);
}

// ------------------------------------------------------------------------------------------------
// Equilibrium: the reactions balance the applied load.
// ------------------------------------------------------------------------------------------------

using test_support::write_file;

std::string plate_case(const std::string& boundary = "rigid = [\"base\"]", const std::string& fem = "",
                       const std::string& mesh = "/meshes/plate2d.geo",
                       const std::string& parameters = "h = 0.01\nlw = 0.02\n") {
  return "[mesh]\nfile = \"" + kSource + mesh + "\"\n[mesh.parameters]\n" + parameters +
         "[material]\nyoung = 206e9\npoisson = 0.3\nthickness = 0.002\n[boundary]\n" + boundary +
         "\n[[load]]\ngroup = \"load\"\ndirection = \"-y\"\nforce = 2.0\n[fem]\n" + fem + "\n";
}

FemResult run_case(const fs::path& file) {
  workbench::CaseFile cf(file);
  auto p = problem_from_case(cf);
  cf.reject_unknown_keys();
  return solve_fem(p);
}

void expect_balance(const FemResult& r, double scale, double tol = 1e-9) {
  for (int a = 0; a < r.dim; ++a) {
    double sum = r.applied[a];
    for (const auto& g : r.reactions) sum += g.force[a];
    EXPECT_NEAR(sum, 0.0, tol * scale) << "axis " << a;
  }
}

TEST(FemEquilibrium, SeedPlateReactionsBalanceTheLoad) {
  workbench::CaseFile cf(kSource + "/cases/seed_plate.toml");
  auto p = problem_from_case(cf);
  const auto r = solve_fem(p);
  EXPECT_EQ(r.n_dofs, 20402u);
  EXPECT_EQ(r.cell_count(), 10000u);
  EXPECT_NEAR(r.applied[1], -2.0, 1e-12);
  ASSERT_EQ(r.reactions.size(), 1u);
  EXPECT_EQ(r.reactions[0].group, "base");
  EXPECT_NEAR(r.reactions[0].force[1], 2.0, 1e-9);
  EXPECT_NEAR(r.reactions[0].force[0], 0.0, 1e-9);
  expect_balance(r, 2.0);
  // The load patch is compressed; the vertical stress integrates to the load on any horizontal cut:
  // row of cells at mid-height, sum sigma_y * h * thickness = -2 N.
  double cut = 0;
  for (std::size_t e = 0; e < r.cell_count(); ++e)
    if (std::abs(r.cell_centres[3 * e + 1] - 0.101) < 1e-6) cut += r.sigma_y[e] * 0.002 * 0.002;
  EXPECT_NEAR(cut, -2.0, 1e-6);
}

TEST(FemEquilibrium, PointLoadQ2AndAmgMatchDirect) {
  const auto direct = run_case(write_file("point_direct.toml",
                                          plate_case("rigid = [\"base\"]", "degree = 2\nload = \"point\"\nsolver = \"direct\"")));
  const auto amg = run_case(write_file("point_amg.toml",
                                       plate_case("rigid = [\"base\"]", "degree = 2\nload = \"point\"\nsolver = \"amg\"\ntolerance = 1e-12")));
  expect_balance(direct, 2.0);
  expect_balance(amg, 2.0);
  EXPECT_GT(amg.iterations, 0);
  EXPECT_LT(amg.iterations, 100);
  EXPECT_LT(amg.residual, 1e-12);
  double umax = 0, diff = 0;
  for (std::size_t i = 0; i < direct.node_displacement.size(); ++i) {
    umax = std::max(umax, std::abs(direct.node_displacement[i]));
    diff = std::max(diff, std::abs(direct.node_displacement[i] - amg.node_displacement[i]));
  }
  EXPECT_GT(umax, 1e-9);
  EXPECT_LT(diff, 1e-8 * umax);
}

TEST(FemEquilibrium, RollersAndClampBalanceInPlaneStrain) {
  // Base on rollers (u_y = 0) and the left side clamped: both carry load.
  const auto r = run_case(write_file(
      "rollers.toml", plate_case("rigid = [\"free\"]\nrollers = [\"base\"]", "model = \"plane_strain\"")));
  ASSERT_EQ(r.reactions.size(), 2u);
  EXPECT_EQ(r.reactions[1].kind, "roller");
  EXPECT_EQ(r.reactions[1].force[0], 0.0);  // a roller in y takes no x force
  EXPECT_GT(r.reactions[1].force[1], 0.01);
  expect_balance(r, 2.0);
  for (std::size_t e = 0; e < r.cell_count(); ++e) ASSERT_NE(r.sigma_z[e], 0.0);  // plane strain
}

TEST(FemEquilibrium, Block3DWithBodyForce) {
  const std::string body =
      "[mesh]\nfile = \"" + kSource +
      "/meshes/block3d.geo\"\n[mesh.parameters]\nh = 0.004\nlw = 0.008\n[material]\nyoung = 206e9\npoisson = 0.3\n"
      "[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\ndirection = \"-y\"\nforce = 5.0\n"
      "[fem]\nbody_force = [0, -77000, 0]\nsolver = \"amg\"\ntolerance = 1e-12\n";
  const auto r = run_case(write_file("block.toml", body));
  const double weight = 77000 * 0.04 * 0.04 * 0.04;
  EXPECT_EQ(r.dim, 3);
  EXPECT_NEAR(r.applied[1], -5.0 - weight, 1e-9);
  expect_balance(r, 5.0 + weight);
  EXPECT_EQ(r.tau_yz.size(), r.cell_count());
}

TEST(FemEquilibrium, TrianglesP2Serial) {
  const auto r = run_case(write_file(
      "triangles.toml", plate_case("rigid = [\"base\"]", "degree = 2", "/tests/fem/meshes/tri_plate.geo", "")));
  EXPECT_EQ(r.cells, "triangle");
  expect_balance(r, 2.0);
}

// ------------------------------------------------------------------------------------------------
// Matrix-free geometric multigrid (solver = "mg") gives the direct solution.
// ------------------------------------------------------------------------------------------------

/// Largest nodal displacement difference relative to the largest displacement; also checks the
/// reactions and every cell stress to the same relative accuracy.
double relative_difference(const FemResult& a, const FemResult& b) {
  EXPECT_EQ(a.n_dofs, b.n_dofs);
  double umax = 0, diff = 0;
  for (std::size_t i = 0; i < a.node_displacement.size(); ++i) {
    umax = std::max(umax, std::abs(a.node_displacement[i]));
    diff = std::max(diff, std::abs(a.node_displacement[i] - b.node_displacement[i]));
  }
  EXPECT_GT(umax, 0.0);
  double smax = 0, sdiff = 0;
  for (std::size_t e = 0; e < a.cell_count(); ++e) {
    smax = std::max(smax, std::abs(a.von_mises[e]));
    sdiff = std::max(sdiff, std::abs(a.sigma_x[e] - b.sigma_x[e]) + std::abs(a.sigma_y[e] - b.sigma_y[e]) +
                                std::abs(a.tau_xy[e] - b.tau_xy[e]));
  }
  double fmax = 0, fdiff = 0;
  for (std::size_t g = 0; g < a.reactions.size(); ++g)
    for (int k = 0; k < 3; ++k) {
      fmax = std::max(fmax, std::abs(a.reactions[g].force[k]));
      fdiff = std::max(fdiff, std::abs(a.reactions[g].force[k] - b.reactions[g].force[k]));
    }
  return std::max({diff / umax, sdiff / smax, fmax > 0 ? fdiff / fmax : 0.0});
}

void expect_mg_matches_direct(const std::string& name, const std::string& boundary, const std::string& fem,
                              const std::string& mesh = "/meshes/plate2d.geo",
                              const std::string& parameters = "h = 0.01\nlw = 0.02\n") {
  const auto direct = run_case(write_file(name + "_direct.toml", plate_case(boundary, fem + "\nsolver = \"direct\"", mesh, parameters)));
  const auto mg = run_case(
      write_file(name + "_mg.toml", plate_case(boundary, fem + "\nsolver = \"mg\"\ntolerance = 1e-12", mesh, parameters)));
  EXPECT_EQ(direct.solver, "direct (CHOLMOD)");
  EXPECT_EQ(mg.solver.rfind("cg+gmg (matrix-free", 0), 0u) << mg.solver;
  EXPECT_GT(mg.iterations, 0);
  EXPECT_LT(mg.iterations, 25) << name;  // flat: 6-12 on these meshes
  EXPECT_LT(mg.residual, 1e-12);
  EXPECT_LT(relative_difference(direct, mg), 1e-9) << name;
  expect_balance(mg, 2.0);
}

TEST(FemMultigrid, Q1PlaneStressMatchesDirect) {
  expect_mg_matches_direct("mg_q1", "rigid = [\"base\"]", "refine = 2");
}

TEST(FemMultigrid, Q2PointLoadMatchesDirect) {
  expect_mg_matches_direct("mg_q2", "rigid = [\"base\"]", "degree = 2\nrefine = 1\nload = \"point\"");
}

TEST(FemMultigrid, RollersAndClampMatchDirect) {
  // One component held on the rollers: the level boundary conditions follow the component mask.
  expect_mg_matches_direct("mg_rollers", "rigid = [\"free\"]\nrollers = [\"base\"]",
                           "refine = 2\nmodel = \"plane_strain\"");
}

TEST(FemMultigrid, Block3DWithBodyForceMatchesDirect) {
  const std::string body =
      "[mesh]\nfile = \"" + kSource +
      "/meshes/block3d.geo\"\n[mesh.parameters]\nh = 0.008\nlw = 0.008\n[material]\nyoung = 206e9\npoisson = 0.3\n"
      "[boundary]\nrigid = [\"base\"]\n[[load]]\ngroup = \"load\"\ndirection = \"-y\"\nforce = 5.0\n"
      "[fem]\nbody_force = [0, -77000, 0]\nrefine = 1\n";
  const auto direct = run_case(write_file("mg_block_direct.toml", body + "solver = \"direct\"\n"));
  const auto mg = run_case(write_file("mg_block_mg.toml", body + "solver = \"mg\"\ntolerance = 1e-12\n"));
  EXPECT_EQ(mg.dim, 3);
  EXPECT_LT(mg.iterations, 25);
  EXPECT_LT(mg.residual, 1e-12);
  EXPECT_LT(relative_difference(direct, mg), 1e-9);
  const double weight = 77000 * 0.04 * 0.04 * 0.04;
  expect_balance(mg, 5.0 + weight);
}

TEST(FemMultigrid, InhomogeneousDisplacementsMatchDirect) {
  // The manufactured problem: every side prescribed (u = g != 0), body force; Q1 and Q2.
  for (int degree : {1, 2}) {
    Manufactured m{2};
    auto p = m.problem(4, degree);
    p.options.refine = degree == 1 ? 3 : 2;
    p.options.solver = SolverKind::Direct;
    const auto direct = solve_fem(p);
    p.options.solver = SolverKind::Mg;
    const auto mg = solve_fem(p);
    EXPECT_EQ(mg.solver.rfind("cg+gmg (matrix-free", 0), 0u) << mg.solver;
    EXPECT_LT(mg.iterations, 25);
    EXPECT_LT(mg.residual, 1e-12);
    EXPECT_LT(relative_difference(direct, mg), 1e-9) << "Q" << degree;
    EXPECT_NEAR(mg.l2_error, direct.l2_error, 1e-9 * direct.l2_error);
    EXPECT_NEAR(mg.h1_error, direct.h1_error, 1e-9 * direct.h1_error);
  }
}

TEST(FemMultigrid, CoarseMlCycleMatchesDirect) {
  // A 2D coarse mesh above 10 x direct_limit (882 DoFs > 500): one ML cycle (rigid body modes) as coarse solve.
  expect_mg_matches_direct("mg_ml_coarse", "rigid = [\"base\"]", "refine = 2\ndirect_limit = 50");
}

TEST(FemMultigrid, Q2CoarseLevelByPCoarseningMatchesDirect) {
  // A Q2 coarse level above direct_limit (3362 DoFs) is not assembled: a p-multigrid to Q1 on the
  // same mesh (882 DoFs) under it, factorised (direct_limit 1000) or one ML cycle (50: 882 > 10 x 50)
  // on Q1; rollers hold one component on the levels of both degrees.
  for (const auto& [name, limit] : {std::pair{"mg_p_direct", "direct_limit = 1000"}, std::pair{"mg_p_ml", "direct_limit = 50"}})
    expect_mg_matches_direct(name, "rigid = [\"base\"]", std::string("degree = 2\nrefine = 1\n") + limit);
  expect_mg_matches_direct("mg_p_rollers", "rigid = [\"free\"]\nrollers = [\"base\"]",
                           "degree = 2\nrefine = 1\ndirect_limit = 50\nmodel = \"plane_strain\"");
  const auto r = run_case(write_file("mg_p_name.toml", plate_case("rigid = [\"base\"]", "degree = 2\nrefine = 1\nsolver = \"mg\"\ndirect_limit = 50")));
  EXPECT_NE(r.solver.find("coarse p-multigrid to Q1 (Chebyshev 4, Q1 ML AMG cycle)"), std::string::npos) << r.solver;
}

TEST(FemMultigrid, AutoPicksMultigridOnLargeQuadMeshes) {
  // 13 122 DoFs > direct_limit, coarse mesh 882 DoFs <= 10 x direct_limit (factorised): geometric multigrid.
  const auto r = run_case(write_file("mg_auto.toml", plate_case("rigid = [\"base\"]", "refine = 2\ndirect_limit = 1000")));
  EXPECT_EQ(r.solver.rfind("cg+gmg (matrix-free", 0), 0u) << r.solver;
  EXPECT_LT(r.residual, 1e-10);  // the default tolerance
  // Coarse mesh above 10 x direct_limit: still multigrid, its coarse level one ML cycle.
  const auto ml_coarse =
      run_case(write_file("mg_auto_ml_coarse.toml", plate_case("rigid = [\"base\"]", "refine = 2\ndirect_limit = 50")));
  EXPECT_NE(ml_coarse.solver.find("coarse ML AMG cycle"), std::string::npos) << ml_coarse.solver;
  EXPECT_LT(relative_difference(r, ml_coarse), 1e-8);
  // An unrefined mesh above direct_limit (multigrid would have a single level): ML on the whole problem.
  const auto ml = run_case(write_file("mg_auto_ml.toml", plate_case("rigid = [\"base\"]", "direct_limit = 500")));
  EXPECT_EQ(ml.n_dofs, 882u);
  EXPECT_EQ(ml.solver, "cg+amg (ML)");
  // Unrefined Q2 above direct_limit: multigrid with one level, the p-multigrid to Q1 under it.
  const auto q2 = run_case(write_file("mg_auto_q2.toml", plate_case("rigid = [\"base\"]", "degree = 2\ndirect_limit = 500")));
  const auto q2_direct = run_case(write_file("mg_auto_q2_direct.toml", plate_case("rigid = [\"base\"]", "degree = 2\nsolver = \"direct\"")));
  EXPECT_EQ(q2.n_dofs, 3362u);
  EXPECT_NE(q2.solver.find("1 levels, Chebyshev 4, coarse p-multigrid to Q1"), std::string::npos) << q2.solver;
  EXPECT_LT(relative_difference(q2_direct, q2), 1e-8);
}

TEST(FemMultigrid, CoarserLevelIsTheCoarseMeshsOwnSolution) {
  // FemOptions::coarser_level: the coarse mesh's solution from the multigrid hierarchy (its load
  // restricted from the fine one) is the FE solution a separate solve on that mesh gives, for
  // tractions; the fine solution started from it is the one started from zero; with a share the
  // fine CG stops early, its residual at that share of where it started.
  // Q2: the coarse level (3362 DoFs) factorised ("direct_limit = 5000") or by p-coarsening (the
  // default 2000, the test above).
  for (const char* degree : {"degree = 1", "degree = 2\ndirect_limit = 5000", "degree = 2"}) {
    auto p = problem_from_case(workbench::CaseFile(write_file("coarse0.toml", plate_case("rigid = [\"base\"]", degree))));
    p.options.solver = fem_reference::SolverKind::Direct;
    const auto coarse = solve_fem(p);
    p.options.refine = 1;
    p.options.solver = fem_reference::SolverKind::Mg;
    const auto fine = solve_fem(p);
    EXPECT_EQ(fine.coarser, nullptr);  // not asked for
    p.options.coarser_level = true;
    const auto nested = solve_fem(p);
    ASSERT_NE(nested.coarser, nullptr) << degree;
    auto without_reactions = coarse;
    without_reactions.reactions.clear();
    EXPECT_TRUE(nested.coarser->reactions.empty());
    EXPECT_LT(relative_difference(without_reactions, *nested.coarser), 1e-8) << degree;
    EXPECT_LT(relative_difference(fine, nested), 1e-8) << degree;
    EXPECT_GT(nested.coarser_start_residual, 1e-3);  // the discretisation error shows in the residual
    p.options.coarser_share = 1e-3;
    const auto early = solve_fem(p);
    EXPECT_LE(early.residual, 1e-3 * early.coarser_start_residual * (1 + 1e-6)) << degree;
    EXPECT_LT(early.iterations, nested.iterations) << degree;
    // A prescribed displacement has no zero lift on the coarse mesh: no coarser level.
    auto moved = p;
    moved.supports[0].kind = fem_reference::SupportKind::Displacement;
    moved.supports[0].displacement = [](const double*, double* u) { u[0] = 0, u[1] = 1e-9; };
    EXPECT_EQ(solve_fem(moved).coarser, nullptr);
  }
}

// ------------------------------------------------------------------------------------------------
// Bad input: one clear line each.
// ------------------------------------------------------------------------------------------------

std::string error_of(const std::string& name, const std::string& body) {
  try {
    run_case(write_file(name, body));
  } catch (const workbench::Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(FemBadInput, GroupTheMeshLacks) {
  const auto e = error_of("bad_group.toml", plate_case("rigid = [\"bottom\"]"));
  EXPECT_NE(e.find("group 'bottom' is not a physical group"), std::string::npos) << e;
  EXPECT_NE(e.find("plate2d.geo"), std::string::npos) << e;
  EXPECT_EQ(e.find('\n'), std::string::npos) << e;
}

TEST(FemBadInput, NoSupports) {
  const auto e = error_of("no_support.toml", plate_case("rigid = []"));
  EXPECT_NE(e.find("no supports"), std::string::npos) << e;
}

TEST(FemBadInput, RollersLeaveRigidMotion) {
  const auto e = error_of("rollers_only.toml", plate_case("rigid = []\nrollers = [\"base\"]"));
  EXPECT_NE(e.find("free to move rigidly (translation along x)"), std::string::npos) << e;
}

TEST(FemBadInput, ElementTypeDealIICannotRead) {
  const auto e = error_of("order2.toml", plate_case("rigid = [\"base\"]", "", "/tests/fem/meshes/tri_order2.geo", ""));
  EXPECT_NE(e.find("Triangle 6"), std::string::npos) << e;
  EXPECT_NE(e.find("cannot read"), std::string::npos) << e;
}

TEST(FemBadInput, OptionsOutOfRange) {
  EXPECT_NE(error_of("degree.toml", plate_case("rigid = [\"base\"]", "degree = 3")).find("fem.degree"),
            std::string::npos);
  EXPECT_NE(error_of("model.toml", plate_case("rigid = [\"base\"]", "model = \"axisymmetric\"")).find("fem.model"),
            std::string::npos);
  EXPECT_NE(error_of("typo.toml", plate_case("rigid = [\"base\"]", "refnie = 2")).find("refnie"), std::string::npos);
}

TEST(FemBadInput, NoConvergenceIsReported) {
  // 20k DoFs: more than ML's coarse direct solve takes, so one CG step cannot converge.
  const auto e = error_of("noconv.toml", plate_case("rigid = [\"base\"]", "solver = \"amg\"\nmax_iterations = 1\ntolerance = 1e-12",
                                                    "/meshes/plate2d.geo", "h = 0.002\nlw = 0.004\n"));
  EXPECT_NE(e.find("did not reach"), std::string::npos) << e;
}

}  // namespace

// FemResult::probes: the solution evaluated at given points. A linear displacement u = B x
// prescribed on the whole boundary is the exact solution (no body force), which Q2 on a refined mesh
// of oblong cells reproduces: at any point inside, u = B x and the plane-stress stress of B's
// strain, to rounding; a point outside the mesh is reported as not found.
TEST(FemProbes, PointValuesReproduceALinearFieldAndMissOutsidePoints) {
  const double B[2][2] = {{1e-3, 2e-4}, {-5e-4, 3e-4}};
  FemProblem p;
  p.young = 200e9;
  p.poisson = 0.25;
  Box box;
  box.lo = {0, 0, 0};
  box.hi = {0.3, 0.2, 0};
  box.cells = {3, 4, 0};
  p.box = box;
  for (const char* g : {"x0", "x1", "y0", "y1"})
    p.supports.push_back({g, SupportKind::Displacement, [&](const double* x, double* u) {
                            for (int i = 0; i < 2; ++i) u[i] = B[i][0] * x[0] + B[i][1] * x[1];
                          }});
  p.options.degree = 2;
  p.options.refine = 1;
  p.options.write_vtu = false;
  p.probe_points = {{0.1234, 0.0567, 0}, {0.2999, 0.1999, 0}, {0.15, 0.1, 0}, {0.31, 0.1, 0}, {-0.01, 0.05, 0}};
  const auto r = solve_fem(p);
  ASSERT_EQ(r.probes.size(), 5u);
  const double E = p.young, nu = p.poisson;
  const double exx = B[0][0], eyy = B[1][1], gxy = B[0][1] + B[1][0];
  const double sx = E / (1 - nu * nu) * (exx + nu * eyy), sy = E / (1 - nu * nu) * (eyy + nu * exx),
               txy = E / (2 * (1 + nu)) * gxy;
  for (int i = 0; i < 3; ++i) {
    const auto& q = r.probes[i];
    const auto& x = p.probe_points[i];
    ASSERT_TRUE(q.found) << "point " << i;
    for (int a = 0; a < 2; ++a) EXPECT_NEAR(q.u[a], B[a][0] * x[0] + B[a][1] * x[1], 1e-12) << "point " << i;
    EXPECT_NEAR(q.sigma[0], sx, 1e-6 * std::abs(sx)) << "point " << i;
    EXPECT_NEAR(q.sigma[1], sy, 1e-6 * std::abs(sx)) << "point " << i;
    EXPECT_NEAR(q.sigma[3], txy, 1e-6 * std::abs(sx)) << "point " << i;
  }
  EXPECT_FALSE(r.probes[3].found);
  EXPECT_FALSE(r.probes[4].found);
}

// The environment that makes a one-process run start MPI in 0.02 s (docs/performance.md): set
// when mpirun did not start the process, never over what the user or mpirun set.
TEST(SingletonMpi, FastStartUpUnlessMpirunOrTheUserDecided) {
  const char* names[] = {"OMPI_MCA_pml", "OMPI_MCA_osc", "OMPI_MCA_ess_singleton_isolated", "OMPI_COMM_WORLD_SIZE",
                         "PMIX_RANK", "PMI_RANK", "SLURM_PROCID", "OMPI_MCA_orte_tmpdir_base", "TMPDIR"};
  std::vector<std::pair<std::string, std::optional<std::string>>> saved;
  for (const char* n : names) {
    const char* v = std::getenv(n);
    saved.emplace_back(n, v ? std::optional<std::string>(v) : std::nullopt);
  }
  auto value = [](const char* n) { const char* v = std::getenv(n); return std::string(v ? v : "(unset)"); };
  auto clear = [&] { for (const char* n : names) ::unsetenv(n); };

  // The session files get a folder of this process's own in TMPDIR (the first call makes it; it is
  // removed at exit), so that two runs at once do not share OpenMPI's /tmp/ompi.<host>.<uid>.
  const std::filesystem::path scratch = test_support::scratch_folder();
  clear();
  ::setenv("TMPDIR", scratch.c_str(), 1);
  fem_reference::configure_singleton_mpi();
  EXPECT_EQ(value("OMPI_MCA_pml"), "ob1");
  EXPECT_EQ(value("OMPI_MCA_osc"), "^ucx");
  EXPECT_EQ(value("OMPI_MCA_ess_singleton_isolated"), "1");
  const std::filesystem::path session = value("OMPI_MCA_orte_tmpdir_base");
  EXPECT_EQ(session.parent_path(), scratch);
  EXPECT_EQ(session.filename().string().rfind("workbench-mpi-", 0), 0u) << session;
  EXPECT_TRUE(std::filesystem::is_directory(session)) << session;

  clear();
  ::setenv("OMPI_MCA_pml", "ucx", 1);  // the user's choice stays
  ::setenv("OMPI_MCA_orte_tmpdir_base", "/var/tmp", 1);
  fem_reference::configure_singleton_mpi();
  EXPECT_EQ(value("OMPI_MCA_pml"), "ucx");
  EXPECT_EQ(value("OMPI_MCA_osc"), "^ucx");
  EXPECT_EQ(value("OMPI_MCA_orte_tmpdir_base"), "/var/tmp");

  for (const char* launcher : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "SLURM_PROCID"}) {  // mpirun, srun
    clear();
    ::setenv(launcher, "2", 1);
    fem_reference::configure_singleton_mpi();
    EXPECT_EQ(value("OMPI_MCA_pml"), "(unset)") << launcher;
    EXPECT_EQ(value("OMPI_MCA_ess_singleton_isolated"), "(unset)") << launcher;
    EXPECT_EQ(value("OMPI_MCA_orte_tmpdir_base"), "(unset)") << launcher;
  }

  clear();
  for (const auto& [n, v] : saved)
    if (v) ::setenv(n.c_str(), v->c_str(), 1);
}
