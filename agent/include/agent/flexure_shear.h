#pragma once
// Saint-Venant's flexure of a prismatic beam of rectangular section (the exact shears of linear
// elasticity under a shear force; Timoshenko & Goodier, "Theory of Elasticity", ch. 12), for the 3D
// columns' shears across a rectangular section (agent/columns.h). Not in the column rule set yet:
// measured, it beats Jourawski beyond about the depth from a bonded clamp but not at it, where the
// clamp's own shears dominate (docs/agent-model.md, "The columns in 3D: measured"). With
// y along the load axis t and z along the width axis w, both from the section's centroid, the
// section h (along t) by d (along w), I = d h^3 / 12 and k = nu / (1 + nu) V / I:
//   tau_at = tau0(y) + k [(3 z^2 - d^2/4) / 6 - d^2 / (2 pi^2) sum_n (-1)^n / n^2 cos(2 n pi z / d) cosh(2 n pi y / d) / cosh(n pi h / d)]
//   tau_aw = k d^2 / (2 pi^2) sum_n (-1)^n / n^2 sin(2 n pi z / d) sinh(2 n pi y / d) / cosh(n pi h / d)
// with Jourawski's tau0 = V / (2 I) (h^2 / 4 - y^2). (tau = (tau0 + dpsi/dz, -dpsi/dy), laplacian
// psi = k z in the rectangle, psi = 0 on its sides: Beltrami-Michell's laplacian tau_at = -V / ((1
// + nu) I), laplacian tau_aw = 0, equilibrium, and no traction on the sides.) The correction to
// tau0 has mean 0 across z at every y: the shears still integrate to V.
#include <vector>

namespace agent {

/// The two shears across the beam axis a [Pa]: along the load axis t and along the width axis w.
struct FlexureShear {
  double at = 0, aw = 0;
};

/// The shears at the point (y, z) [m] (from the centroid, |y| <= h / 2, |z| <= d / 2) of an h by d
/// rectangle [m] under the shear force `shear` [N] (tau_at's sign: Jourawski's tau0 = shear / (2 I)
/// (h^2 / 4 - y^2)) for Poisson's ratio `poisson`: tau0 plus the correction in at, the whole tau_aw.
/// The series is summed until its terms are below 1e-16 of the first (at most 10^5 terms: on the
/// sides y = +-h/2 they fall only as 1 / n^2).
FlexureShear flexure_shear(double y, double z, double h, double d, double shear, double poisson);

/// The correction alone (flexure_shear less tau0; tau_aw whole) averaged over each box [y_planes[j],
/// y_planes[j + 1]] x [z_planes[k], z_planes[k + 1]] (increasing planes [m] from the centroid,
/// within the rectangle), in closed form (the products integrate exactly); the result's box (j, k)
/// is element j * (z_planes.size() - 1) + k. Over boxes spanning the width the at means weighted by
/// their widths sum to 0 (to round-off) at every j. Summed until the terms' bound falls below 1e-16
/// of the first.
std::vector<FlexureShear> flexure_correction_means(const std::vector<double>& y_planes, const std::vector<double>& z_planes,
                                                   double h, double d, double shear, double poisson);

}  // namespace agent
