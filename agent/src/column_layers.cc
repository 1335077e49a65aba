// The column rule set's layers across the beam under a clamp: the clamp's restraint and the loads'
// push into the section (column_layers.h).
#include "column_layers.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace agent {

/// The clamp's layer: the bonded clamp holds the section's strains across the beam (eps_t = 0, in
/// 3D eps_w = 0 too), so on its plane sigma_t = nu sigma_a (2D, plane stress), sigma_t = sigma_w =
/// nu / (1 - nu) sigma_a (3D), and that restraint decays away from it as the strip's end effects
/// do: exp(-d / l), l = H / 7.4977 (Papkovich-Fadle: the first antisymmetric root of sin 2k = -2k, H
/// the clamp column's section depth along t; for sigma_w its width along w), faster near a free face across that component's axis
/// (where it vanishes): l = 1 / sqrt(l^-2 + f^-2), f the agent centre's distance to the nearest free
/// face along t (sigma_t) or w (sigma_w). Each agent takes the decay's mean over its length along
/// a, as face forces on its faces across t (and w). Its shears across (3D): clamp_shears.
void clamp_layer(const Grid& g, const Material& material, const Columns& c, const ColumnAgents& ca, TransferResults& out) {
  if (c.plan.holding != Holding::Clamp) return;
  const int a = c.plan.axis, t = c.plan.across, wa = c.plan.width_axis(), n = g.cells[a];
  const bool high = is_positive(c.plan.clamp_side);  // the clamp at the body's high end along a
  const std::size_t root = high ? std::size_t(n) - 1 : 0;
  const double nu = material.poisson, k = g.dim == 3 ? nu / (1 - nu) : nu;
  const double h = g.size[t], l0 = double(c.last_row[root] - c.first_row[root] + 1) * h / 7.4977;
  const std::size_t faces = 2 * std::size_t(g.dim);
  // 3D: sigma_w's restraint decays over the section's width along w as sigma_t's over its depth.
  double lw = 0;
  if (g.dim == 3) {
    const auto w = std::minmax_element(ca.across.begin() + std::ptrdiff_t(ca.start[root]),
                                       ca.across.begin() + std::ptrdiff_t(ca.start[root + 1]));
    lw = double(*w.second - *w.first + 1) * g.size[wa] / 7.4977;
  }
  // The mean over [d, d + ds] of exp(-x / l), l (l0 or lw) shortened by the distance f to a free face.
  auto decay = [](double l_axis, double d, double ds, double f) {
    const double l = 1 / std::sqrt(1 / (l_axis * l_axis) + 1 / (f * f));
    return l / ds * (std::exp(-d / l) - std::exp(-(d + ds) / l));
  };
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const double near = high ? c.plan.at[0] - g.plane(a, int(i) + 1) : g.plane(a, int(i)) - c.plan.at[0];
    if (near > 40 * std::max(l0, lw)) continue;  // exp(-40): nothing left
    const std::size_t first = ca.start[i], last = ca.start[i + 1] - 1;  // the column's agents, sorted along t
    const bool low_free = c.first_row[i] == ca.rows[first], high_free = c.last_row[i] == ca.rows[last];
    int w0 = 0, w1 = 0;  // 3D: the column's extent along w
    if (g.dim == 3) {
      w0 = *std::min_element(ca.across.begin() + std::ptrdiff_t(first), ca.across.begin() + std::ptrdiff_t(last) + 1);
      w1 = *std::max_element(ca.across.begin() + std::ptrdiff_t(first), ca.across.begin() + std::ptrdiff_t(last) + 1);
    }
    for (std::size_t q = first; q <= last; ++q) {
      const int row = ca.rows[q];
      if (!c.in_section(i, row)) continue;
      const double ft = std::min(low_free ? (row - c.first_row[i] + 0.5) * h : HUGE_VAL,
                                 high_free ? (c.last_row[i] - row + 0.5) * h : HUGE_VAL);
      const std::size_t cell = ca.agents[q];
      const double sigma_a = -out.faces[cell * faces + std::size_t(direction(a, false))] / g.face_area(a);
      auto write = [&](int axis, double mean) {
        out.faces[cell * faces + std::size_t(direction(axis, false))] = out.faces[cell * faces + std::size_t(direction(axis, true))] =
            -k * sigma_a * mean * g.face_area(axis);
      };
      write(t, decay(l0, near, c.width[i], ft));
      if (g.dim == 3) {
        const int col = ca.across[q];
        write(wa, decay(lw, near, c.width[i], std::min(col - w0 + 0.5, w1 - col + 0.5) * g.size[wa]));
      }
    }
  }
}

/// The clamp's shears (3D): the layer's sigma_w and sigma_t vary across the section, so the
/// equilibrium across the beam needs d tau_aw / da = -d sigma_w / dw and d tau_at / da = -d sigma_t
/// / dt beside what the columns carry; integrated along a from the free end (zero there) toward the
/// clamp, each derivative across an agent its two faces' difference (a face between two agents of
/// the section holds their mean, a free face 0: so each level's and each row's derivatives sum to 0
/// and the section's shears still integrate to v across t and to 0 across w). tau_aw is set, tau_at
/// added to Jourawski's.
void clamp_shears(const Grid& g, const Columns& c, const ColumnAgents& ca, TransferResults& out) {
  if (c.plan.holding != Holding::Clamp || g.dim != 3) return;
  const int a = c.plan.axis, t = c.plan.across, wa = c.plan.width_axis(), n = g.cells[a];
  const bool high = is_positive(c.plan.clamp_side);
  const std::size_t faces = 6, shears = std::size_t(shear_count(3));
  const std::size_t at = std::size_t(shear_pair(a, t)), aw = std::size_t(shear_pair(a, wa));
  auto sigma = [&](std::size_t cell, int axis) {
    return -out.faces[cell * faces + std::size_t(direction(axis, false))] / g.face_area(axis);
  };
  // d sigma_axis / d axis across `cell` (of column i, at `row`): its faces' difference over its length
  auto derivative = [&](std::size_t cell, int axis, std::size_t i, int row) {
    const double own = sigma(cell, axis);
    double face[2] = {0, 0};
    for (int up = 0; up < 2; ++up) {
      const std::size_t next = g.neighbour(cell, direction(axis, up == 1));
      const int next_row = axis == t ? row + (up == 1 ? 1 : -1) : row;
      if (next != Grid::npos && !g.is_air(next) && c.in_section(i, next_row)) face[up] = 0.5 * (own + sigma(next, axis));
    }
    return (face[1] - face[0]) / g.size[axis];
  };
  const std::size_t lines = std::size_t(g.cells[t]) * std::size_t(g.cells[wa]);
  std::vector<double> sum_w(lines, 0.0), sum_t(lines, 0.0);  // per line along a, the integrals so far
  const double sign = high ? -1.0 : 1.0;                       // scanned from the free end toward the clamp
  for (int step = 0; step < n; ++step) {
    const std::size_t i = std::size_t(high ? step : n - 1 - step);
    const double h_a = c.width[i];
    for (std::size_t q = ca.start[i]; q < ca.start[i + 1]; ++q) {
      const int row = ca.rows[q];
      if (!c.in_section(i, row)) continue;
      const std::size_t cell = ca.agents[q], line = std::size_t(row) * std::size_t(g.cells[wa]) + std::size_t(ca.across[q]);
      const double dw = derivative(cell, wa, i, row), dt = derivative(cell, t, i, row);
      out.shear[cell * shears + aw] = sign * (sum_w[line] + 0.5 * dw * h_a);
      out.shear[cell * shears + at] += sign * (sum_t[line] + 0.5 * dt * h_a);
      sum_w[line] += dw * h_a, sum_t[line] += dt * h_a;
    }
  }
}

/// The loads' layer under a clamp (2D): a load enters its agent's face and pushes along t into the
/// section, which passes it to the columns' shear over the depth: each load's sigma_t is -F / (b
/// s) P(e) within s = ds + 2 d along a (spread at 45 degrees from the agent's face, clipped to the
/// body; each agent by the share of its length inside), d the depth below the loaded face, P(e) = (2 - 3 e + e^3) / 4 the profile of a beam loaded
/// on one face (1 there, 0 on the far face; e = 2 d / D - 1, D the column's section depth from the
/// loaded face), added to what the faces across t hold. Only a push on a boundary face across t (a
/// load along a face, as an inclined load's part, has none). Between supports and in 3D: not built.
void load_layer(const Grid& g, const Columns& c, const ColumnAgents& ca, const std::vector<EntryLoad>& loads, TransferResults& out) {
  if (c.plan.holding != Holding::Clamp || g.dim != 2) return;
  const int a = c.plan.axis, t = c.plan.across, n = g.cells[a];
  const double h = g.size[t], b = g.thickness, lo = g.plane(a, 0), hi = g.plane(a, n), reach = g.plane(t, g.cells[t]) - g.plane(t, 0);
  const std::size_t faces = 2 * std::size_t(g.dim);
  for (const auto& l : loads) {
    if (g.has_neighbour(l.cell, opposite(l.dir))) continue;  // a traction along a face (a shear), not a push on it
    const int i0 = g.coords(l.cell)[a], down = is_positive(l.dir) ? 1 : -1;  // rows along the push
    const double entry = g.centre(l.cell)[t] - down * 0.5 * h;              // the loaded face along t
    const double s0 = g.plane(a, i0), s1 = g.plane(a, i0 + 1);
    for (std::size_t i = 0; i < std::size_t(n); ++i) {
      if (g.plane(a, int(i) + 1) < s0 - reach || g.plane(a, int(i)) > s1 + reach) continue;  // beyond any spread
      const double far = down > 0 ? g.plane(t, c.last_row[i] + 1) : g.plane(t, c.first_row[i]);
      const double depth = (far - entry) * down;  // the section ahead of the loaded face
      for (std::size_t q = ca.start[i]; q < ca.start[i + 1] && depth > 0; ++q) {
        const std::size_t cell = ca.agents[q];
        const double d = (g.centre(cell)[t] - entry) * down, from = std::max(lo, s0 - d), to = std::min(hi, s1 + d);
        // The share of the agent's length inside the spread (a row's sigma_t integrates to F P(e)).
        const double inside = std::min(to, g.plane(a, int(i) + 1)) - std::max(from, g.plane(a, int(i))), e = 2 * d / depth - 1;
        if (d <= 0 || inside <= 0 || !c.in_section(i, ca.rows[q])) continue;
        const double sigma = -l.force / (b * (to - from)) * (2 - 3 * e + e * e * e) / 4 * inside / c.width[i];
        for (bool side : {false, true}) out.faces[cell * faces + std::size_t(direction(t, side))] -= sigma * g.face_area(t);
      }
    }
  }
}

}  // namespace agent
