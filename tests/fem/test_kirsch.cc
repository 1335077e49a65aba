// Kirsch's plate with a circular hole in tension: the FEM reference's stress concentration on a
// fine mesh of the true (smooth) geometry against the closed form (factor 3 at the hole's top).
#include <fem_reference/fem_case.h>
#include <workbench/case_file.h>

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <utility>
#include <vector>
#include <filesystem>
#include <fstream>

#include <unistd.h>

namespace fs = std::filesystem;

namespace {

const std::string kSource = WORKBENCH_SOURCE_DIR;

// sigma_x / S on the line x = 0 (theta = 90 degrees) at distance r, infinite plate (Kirsch).
double kirsch_sigma_x(double r, double R) {
  const double q = (R / r) * (R / r);
  return 1 + 0.5 * q + 1.5 * q * q;
}

}  // namespace

TEST(FemKirsch, HoleInTensionConcentratesTheStressThreefold) {
  // A quarter of a 400 x 400 mm plate, hole R = 10 mm (d / W = 0.05: the finite width raises the
  // factor by under 0.3 %), symmetry rollers, S = 1 MPa on the far edge (1 mm thick: 0.2 m x
  // 1e-3 m x 1e6 Pa = 200 N), P2 triangles of R / 20 at the rim.
  const double L = 0.2, R = 0.01, S = 1e6;
  const fs::path dir = fs::temp_directory_path() / ("workbench_kirsch_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path file = dir / "kirsch.toml";
  std::ofstream(file) << "[mesh]\nfile = \"" << kSource << "/tests/fem/meshes/quarter_hole.geo\"\n"
                      << "[material]\nyoung = 206e9\npoisson = 0.3\nthickness = 0.001\n"
                      << "[boundary]\nrigid = []\nrollers = [\"sym_x\", \"sym_y\"]\n"
                      << "[[load]]\ngroup = \"pull\"\ndirection = \"+x\"\nforce = " << S * L * 0.001 << "\n"
                      << "[fem]\ndegree = 2\nmodel = \"plane_stress\"\n";
  workbench::CaseFile cf(file);
  auto problem = fem_reference::problem_from_case(cf);
  cf.reject_unknown_keys();
  const auto result = fem_reference::solve_fem(problem);
  fs::remove_all(dir);

  // The peak: the largest cell value of sigma_x. A cell value is the cell's mean, so it sits
  // about half a rim cell (h = R / 20) from the rim, where Kirsch's field is 3 - 7 (h / 2) / R
  // = 2.83 S; the tolerance 0.2 S covers that gradient, the finite width (+0.01 S) and the
  // discretisation.
  double peak = 0;
  std::size_t at = 0;
  for (std::size_t e = 0; e < result.cell_count(); ++e)
    if (result.sigma_x[e] > peak) {
      peak = result.sigma_x[e];
      at = e;
    }
  EXPECT_NEAR(peak / S, 3.0, 0.2);
  EXPECT_NEAR(peak / S, kirsch_sigma_x(std::hypot(result.cell_centres[3 * at], result.cell_centres[3 * at + 1]), R),
              0.015 * 3);
  const double x = result.cell_centres[3 * at], y = result.cell_centres[3 * at + 1];
  EXPECT_LT(x, R / 5) << "the peak is at the hole's top (theta = 90 degrees)";
  EXPECT_LT(std::hypot(x, y), 1.1 * R);
  // Along theta = 90 degrees, each cell against Kirsch's field at its own centre: within 1.5 %
  // (measured: FEM 0.5-0.7 % above, the finite width's share) from the rim to 3 R.
  std::vector<std::pair<double, double>> line;  // (r / R, sigma_x / S)
  for (std::size_t e = 0; e < result.cell_count(); ++e) {
    const double cx = result.cell_centres[3 * e], cy = result.cell_centres[3 * e + 1];
    const double r = std::hypot(cx, cy);
    if (cx < 0.05 * r && r < 3 * R) {
      EXPECT_NEAR(result.sigma_x[e] / S, kirsch_sigma_x(r, R), 0.015 * kirsch_sigma_x(r, R)) << "r / R = " << r / R;
      line.push_back({r / R, result.sigma_x[e] / S});
    }
  }
  ASSERT_GT(line.size(), 10u);
  // The factor itself: the two cells nearest the rim on that line, extrapolated linearly to r = R
  // (Kirsch's own curve, so extrapolated from radii 1.012 R and 1.029 R, gives 2.994; measured 3.005):
  // within 0.05 of 3.
  std::sort(line.begin(), line.end());
  const auto first = line[0];
  const auto second = *std::find_if(line.begin(), line.end(), [&](const auto& p) { return p.first > first.first + 0.01; });
  const double factor = first.second + (1.0 - first.first) * (second.second - first.second) / (second.first - first.first);
  EXPECT_NEAR(factor, 3.0, 0.05);
  // Far from the hole the plate carries S.
  for (std::size_t e = 0; e < result.cell_count(); ++e)
    if (result.cell_centres[3 * e] > 0.9 * L) {
      EXPECT_NEAR(result.sigma_x[e] / S, 1.0, 0.02);
    }
}
