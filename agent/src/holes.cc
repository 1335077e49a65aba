// A 2D grid's holes and the shear about each (Kirsch), which the turning paths' stress
// components add (agent/stress_components.h, hole_shear).
#include <agent/stress_components.h>

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace agent {

namespace {
/// Radii about a hole that its shear reaches: the disturbance of the uniform field falls off as
/// (radius / r)^2, at 10 radii a percent of the remote stress; leaving out what lies beyond keeps a
/// hole's cost to the agents about it (a plate of many holes stays linear in its agents).
constexpr double kHoleReach = 10;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

std::vector<Hole> enclosed_holes(const Grid& g) {
  std::vector<Hole> holes;
  if (g.dim != 2) return holes;
  const int nx = g.cells[0], ny = g.cells[1];
  auto air = [&](int i, int j) {
    const std::size_t c = g.index(i, j, 0);
    return c == Grid::npos || g.is_air(c);
  };
  std::vector<char> seen(std::size_t(nx) * ny, 0);
  std::vector<std::array<int, 2>> stack;
  for (int j0 = 0; j0 < ny; ++j0)
    for (int i0 = 0; i0 < nx; ++i0) {
      if (seen[i0 + std::size_t(nx) * j0] || !air(i0, j0)) continue;
      Hole h;
      bool enclosed = true;  // air that reaches the box's side is outside the body, not a hole
      double cx = 0, cy = 0;
      stack.assign(1, {i0, j0});
      seen[i0 + std::size_t(nx) * j0] = 1;
      while (!stack.empty()) {
        const auto [i, j] = stack.back();
        stack.pop_back();
        enclosed = enclosed && i > 0 && j > 0 && i < nx - 1 && j < ny - 1;
        const double wx = g.plane(0, i + 1) - g.plane(0, i), wy = g.plane(1, j + 1) - g.plane(1, j);
        h.area += wx * wy;
        cx += wx * wy * 0.5 * (g.plane(0, i) + g.plane(0, i + 1));
        cy += wx * wy * 0.5 * (g.plane(1, j) + g.plane(1, j + 1));
        for (const auto& step : {std::array<int, 2>{1, 0}, std::array<int, 2>{-1, 0}, std::array<int, 2>{0, 1},
                                 std::array<int, 2>{0, -1}}) {
          const int p = i + step[0], q = j + step[1];
          if (p < 0 || q < 0 || p >= nx || q >= ny || seen[p + std::size_t(nx) * q] || !air(p, q)) continue;
          seen[p + std::size_t(nx) * q] = 1;
          stack.push_back({p, q});
        }
      }
      if (!enclosed) continue;
      h.centre[0] = cx / h.area;
      h.centre[1] = cy / h.area;
      holes.push_back(h);
    }
  return holes;
}

double kirsch_shear(double along, double across, double radius, double remote) {
  const double distance = std::hypot(along, across), r = std::max(distance, radius);
  if (!(distance > 0)) return 0.0;  // the centre: no direction (and inside the hole)
  const double c = along / distance, s = across / distance;
  const double q2 = radius * radius / (r * r), q4 = q2 * q2;
  const double c2 = c * c - s * s, s2 = 2 * s * c;  // cos 2 theta, sin 2 theta
  // Kirsch's polar components, rotated into the (along, across) frame.
  const double srr = 0.5 * remote * (1 - q2) + 0.5 * remote * (1 - 4 * q2 + 3 * q4) * c2;
  const double stt = 0.5 * remote * (1 + q2) - 0.5 * remote * (1 + 3 * q4) * c2;
  const double srt = -0.5 * remote * (1 + 2 * q2 - 3 * q4) * s2;
  return (srr - stt) * s * c + srt * c2;
}

std::vector<double> hole_shear(const Grid& g, int a, const std::vector<double>& normal) {
  std::vector<double> tau(g.count(), 0.0);
  if (g.dim != 2) return tau;
  const int l = 1 - a;
  for (const Hole& h : enclosed_holes(g)) {
    // The remote stress: the force through the row at the hole's centre over the row's extent
    // (the gross section: a row through a hole carries the load of the whole width).
    int row = 0;
    while (row + 1 < g.cells[a] && g.plane(a, row + 1) <= h.centre[a]) ++row;
    double force = 0, lo = 1e300, hi = -1e300, below = 0, above = 0;  // the body's width on each side
    for (int i = 0; i < g.cells[l]; ++i) {
      const std::size_t c = a == 0 ? g.index(row, i, 0) : g.index(i, row, 0);
      if (c == Grid::npos || g.is_air(c)) continue;
      const double width = g.plane(l, i + 1) - g.plane(l, i);
      force += normal[c * 2 + a] * width;
      lo = std::min(lo, g.plane(l, i));
      hi = std::max(hi, g.plane(l, i + 1));
      (g.plane(l, i) < h.centre[l] ? below : above) += width;
    }
    const double remote = force / (hi - lo), radius = std::sqrt(h.area / kPi);
    // Kirsch's plate is infinite: a hole beside which the body is narrower than its radius (a
    // ring's inside, a slot) is not one; its walls carry the load as beams.
    if (!(hi > lo) || force == 0 || below < radius || above < radius) continue;
    // The agents within kHoleReach radii of its centre.
    int from[2], to[2];
    for (int d = 0; d < 2; ++d) {
      from[d] = 0;
      while (from[d] + 1 < g.cells[d] && g.plane(d, from[d] + 1) <= h.centre[d] - kHoleReach * radius) ++from[d];
      to[d] = from[d];
      while (to[d] + 1 < g.cells[d] && g.plane(d, to[d] + 1) < h.centre[d] + kHoleReach * radius) ++to[d];
    }
    for (int j = from[1]; j <= to[1]; ++j)
      for (int i = from[0]; i <= to[0]; ++i) {
        const std::size_t c = g.index(i, j, 0);
        if (c == Grid::npos || g.is_air(c)) continue;
        const Eigen::Vector3d x = g.centre(c);
        tau[c] += kirsch_shear(x[a] - h.centre[a], x[l] - h.centre[l], radius, remote);
      }
  }
  return tau;
}

}  // namespace agent
