// The column rule set: statics, the bonded thrust, Navier and Jourawski per column, the march of
// the displacement (agent/columns.h).
#include <agent/columns.h>

#include "column_layers.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace agent {

namespace {

[[noreturn]] void refuse(const std::string& why) { throw std::invalid_argument(why); }

std::string mm(double x) {
  std::ostringstream s;
  s << 1e3 * x << " mm";
  return s.str();
}

/// Centre of column i along `a` [m], as Grid::centre computes it.
double column_centre(const Grid& g, int a, int i) {
  return g.planes[a].empty() ? g.origin[a] + (i + 0.5) * g.size[a] : 0.5 * (g.plane(a, i) + g.plane(a, i + 1));
}

/// An agent's extent along the third axis w: its edge in 3D, the thickness in 2D [m].
double agent_width(const Grid& g, int w) { return g.dim == 3 ? g.size[w] : g.thickness; }

/// A force across the beam axis at `s` along it [N], and a couple [N m] (the clamp's).
struct Force {
  double s, f, couple;
};

/// Separate runs of the coordinates along `b` of `faces`' cells (1: one stretch, 0: no face).
int stretches_along(const Grid& g, const std::vector<BoundaryFace>& faces, int b) {
  std::vector<int> at;
  for (const auto& f : faces) at.push_back(g.coords(f.cell)[b]);
  std::sort(at.begin(), at.end());
  int runs = 0;
  for (std::size_t k = 0; k < at.size(); ++k) runs += k == 0 || at[k] > at[k - 1] + 1;
  return runs;
}

/// The beam axis of a 3D body under loads along t: the normal of the rigid faces across it (a
/// clamp), or, where every rigid face is along t (supports), the one axis across t along which they
/// lie apart (the longer of the two when they form one stretch: plan_columns then says so).
int beam_axis_3d(const Grid& g, int t) {
  std::vector<BoundaryFace> along_t;
  int clamp = -1;
  for (const auto& f : g.boundary_faces()) {
    if (g.boundary(f.side, f.cell) != Boundary::Rigid) continue;
    const int n = axis_of(f.side);
    if (n == t) {
      along_t.push_back(f);
    } else if (clamp < 0 || clamp == n) {
      clamp = n;
    } else {
      refuse(std::string("rigid faces across both ") + char('x' + std::min(clamp, n)) + " and " +
             char('x' + std::max(clamp, n)) + " (clamps on two sides): not built");
    }
  }
  if (clamp >= 0) return clamp;
  if (along_t.empty()) refuse("no rigid face");
  const int b0 = t == 0 ? 1 : 0, b1 = t == 2 ? 1 : 2;  // the axes across t
  const bool apart0 = stretches_along(g, along_t, b0) > 1, apart1 = stretches_along(g, along_t, b1) > 1;
  if (apart0 && apart1)
    refuse(std::string("the rigid faces along ") + char('x' + t) + " lie apart along both " + char('x' + b0) + " and " +
           char('x' + b1) + " (a plate on point supports): the columns need supports along one beam axis");
  if (apart0 != apart1) return apart0 ? b0 : b1;
  return g.cells[b1] > g.cells[b0] ? b1 : b0;
}

}  // namespace

bool clamped(const Grid& g, const std::vector<EntryLoad>& loads) {
  try {
    return plan_columns(g, loads).holding == Holding::Clamp;
  } catch (const std::invalid_argument&) {
    return false;
  }
}

std::string describe(const ColumnPlan& p) {
  const char a = char('x' + p.axis);
  std::ostringstream s;
  s << "bending: columns along " << a << " to ";
  if (p.holding == Holding::Clamp)
    s << "the clamp at " << a << " = " << mm(p.at[0]);
  else
    s << "the supports at " << a << " = " << mm(p.at[0]) << " and " << mm(p.at[1]);
  return s.str();
}

ColumnPlan plan_columns(const Grid& g, const std::vector<EntryLoad>& loads) {
  if (loads.empty()) refuse("no load");
  const int t = axis_of(loads.front().dir);
  for (const auto& l : loads)
    if (axis_of(l.dir) != t)
      refuse(std::string("loads along both ") + char('x' + std::min(t, axis_of(l.dir))) + " and " +
             char('x' + std::max(t, axis_of(l.dir))) + ": the columns carry loads across one beam axis");
  ColumnPlan p;
  p.across = t;
  p.axis = g.dim == 2 ? 1 - t : beam_axis_3d(g, t);
  const int a = p.axis;
  const char an = char('x' + a);
  std::vector<char> filled(std::size_t(g.cells[a]), 0);
  for (std::size_t c = 0; c < g.count(); ++c)
    if (!g.is_air(c)) filled[std::size_t(g.coords(c)[a])] = 1;
  for (int i = 0; i < g.cells[a]; ++i)
    if (!filled[std::size_t(i)])
      refuse(std::string("no agent between ") + an + " = " + mm(g.plane(a, i)) + " and " + mm(g.plane(a, i + 1)) +
             ": the body is not one beam along " + an);
  std::vector<BoundaryFace> clamp, supports;
  for (const auto& f : g.boundary_faces())
    if (g.boundary(f.side, f.cell) == Boundary::Rigid) (axis_of(f.side) == a ? clamp : supports).push_back(f);
  if (clamp.empty() && supports.empty()) refuse("no rigid face");
  if (!clamp.empty() && !supports.empty())
    refuse(std::string("rigid faces both across the beam axis ") + an + " (a clamp) and along it (supports): not built");
  if (!clamp.empty()) {
    p.holding = Holding::Clamp;
    p.clamp_side = clamp.front().side;
    auto plane_of = [&](const BoundaryFace& f) { return g.coords(f.cell)[a] + (is_positive(f.side) ? 1 : 0); };
    const int plane = plane_of(clamp.front());
    for (const auto& f : clamp)
      if (f.side != p.clamp_side || plane_of(f) != plane)
        refuse(std::string("rigid faces across the beam axis ") + an +
               " on more than one plane (clamped at both ends, or a stepped clamp): an indeterminate beam, not built");
    if (plane != (is_positive(p.clamp_side) ? g.cells[a] : 0))
      refuse(std::string("the clamp (rigid faces ") + kDirectionNames[p.clamp_side] + " at " + an + " = " +
             mm(g.plane(a, plane)) + ") is not at the end of the body: agents lie beyond it");
    p.at[0] = g.plane(a, plane);
    p.rigid_area = double(clamp.size()) * g.face_area(a);
    return p;
  }
  p.holding = Holding::Supports;
  const int side = supports.front().side;
  auto level_of = [&](const BoundaryFace& f) { return g.coords(f.cell)[t] + (is_positive(f.side) ? 1 : 0); };
  const int level = level_of(supports.front());
  for (const auto& f : supports)
    if (f.side != side || level_of(f) != level)
      refuse(std::string("rigid faces along the beam axis ") + an + " on more than one plane (on both sides, or at two levels): not built");
  std::sort(supports.begin(), supports.end(),
            [&](const BoundaryFace& x, const BoundaryFace& y) { return g.coords(x.cell)[a] < g.coords(y.cell)[a]; });
  std::vector<std::pair<double, int>> stretches;  // (sum of face centres along a, faces)
  int last = -2;
  for (const auto& f : supports) {
    const int i = g.coords(f.cell)[a];
    if (i > last + 1) stretches.push_back({0.0, 0});
    stretches.back().first += column_centre(g, a, i), stretches.back().second += 1;
    last = i;
  }
  if (stretches.size() == 1)
    refuse(std::string("the rigid faces along the beam axis ") + an +
           " form one support: the columns need a clamp or two supports (a load onto a support ahead of it is carried by "
           "the other rule sets)");
  if (stretches.size() > 2)
    refuse(std::to_string(stretches.size()) + " supports along " + an + ": an indeterminate beam, not built (the columns need a clamp or two supports)");
  for (int k = 0; k < 2; ++k) p.at[std::size_t(k)] = stretches[std::size_t(k)].first / stretches[std::size_t(k)].second;
  p.support_level = g.plane(t, level);
  p.rigid_area = double(supports.size()) * g.face_area(t);
  return p;
}

namespace {

/// Each column's section rows (Columns::first_row, last_row): its agents' extent along t; under a
/// clamp narrowed, from the column farthest from it toward it, to the previous column's section
/// widened by the column's width each way (45 degrees); and the stresses' core and reach.
void section_rows(const Grid& g, Columns& c) {
  const int a = c.plan.axis, t = c.plan.across, n = g.cells[a];
  c.first_row.assign(std::size_t(n), g.cells[t]), c.last_row.assign(std::size_t(n), -1);
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell)) {
      const auto p = g.coords(cell);
      const std::size_t i = std::size_t(p[a]);
      c.first_row[i] = std::min(c.first_row[i], p[t]), c.last_row[i] = std::max(c.last_row[i], p[t]);
    }
  c.core_first = c.first_row, c.core_last = c.last_row;
  c.reach_low.assign(std::size_t(n), 0.0), c.reach_high.assign(std::size_t(n), 0.0);
  if (c.plan.holding != Holding::Clamp) return;
  const bool from_low = is_positive(c.plan.clamp_side);  // the clamp at the high end: spread from column 0
  // The stresses' core and reach (Columns::weight): a column without agents beside the core (a beam
  // that turns back on itself) is whole.
  for (int k = 1; k < n; ++k) {
    const std::size_t i = std::size_t(from_low ? k : n - 1 - k), prev = std::size_t(from_low ? k - 1 : n - k);
    const double spread = (g.plane(a, int(i) + 1) - g.plane(a, int(i))) / g.size[t];
    const int lo = std::max(c.first_row[i], c.core_first[prev]), hi = std::min(c.last_row[i], c.core_last[prev]);
    if (lo > hi) continue;
    c.core_first[i] = lo, c.core_last[i] = hi;
    c.reach_low[i] = lo > c.first_row[i] ? c.reach_low[prev] + spread : 0.0;
    c.reach_high[i] = hi < c.last_row[i] ? c.reach_high[prev] + spread : 0.0;
  }
  double lo = 0, hi = 0;  // the section's extent in rows, spreading
  for (int k = 0; k < n; ++k) {
    const std::size_t i = std::size_t(from_low ? k : n - 1 - k);
    const double spread = (g.plane(a, int(i) + 1) - g.plane(a, int(i))) / g.size[t];
    lo = k == 0 ? c.first_row[i] : std::max(double(c.first_row[i]), lo - spread);
    hi = k == 0 ? c.last_row[i] : std::min(double(c.last_row[i]), hi + spread);
    c.first_row[i] = int(std::ceil(lo - 1e-9)), c.last_row[i] = int(std::floor(hi + 1e-9));
  }
  // A column whose agents all lie beyond the spread (a beam that turns back on itself): all of them.
  std::vector<char> held(std::size_t(n), 0);
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell) && c.in_section(std::size_t(g.coords(cell)[a]), g.coords(cell)[t])) held[std::size_t(g.coords(cell)[a])] = 1;
  for (std::size_t cell = 0; cell < g.count(); ++cell) {
    if (g.is_air(cell)) continue;  // (first: a tiled grid's air slots may lie beyond the box)
    const std::size_t i = std::size_t(g.coords(cell)[a]);
    if (!held[i]) c.first_row[i] = std::min(c.first_row[i], g.coords(cell)[t]), c.last_row[i] = std::max(c.last_row[i], g.coords(cell)[t]);
  }
}

}  // namespace

Columns column_statics(const Grid& g, const std::vector<EntryLoad>& loads) {
  Columns c;
  c.plan = plan_columns(g, loads);
  const int a = c.plan.axis, t = c.plan.across, wa = c.plan.width_axis(), n = g.cells[a];
  const double h = g.size[t], w = agent_width(g, wa);
  section_rows(g, c);
  // Sections: sums over each column's agents, positions from the box's lower side (less round-off).
  std::vector<double> count(std::size_t(n), 0.0), sum(std::size_t(n), 0.0), sum2(std::size_t(n), 0.0);
  std::vector<double> sum_w(g.dim == 3 ? std::size_t(n) : 0, 0.0);
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell) && c.in_section(std::size_t(g.coords(cell)[a]), g.coords(cell)[t])) {
      const std::size_t i = std::size_t(g.coords(cell)[a]);
      const double r = g.centre(cell)[t] - g.origin[t];
      count[i] += 1, sum[i] += r, sum2[i] += r * r;
      if (g.dim == 3) sum_w[i] += g.centre(cell)[wa] - g.origin[wa];
    }
  c.area.resize(std::size_t(n)), c.centroid.resize(std::size_t(n)), c.inertia.resize(std::size_t(n));
  c.centre.resize(std::size_t(n)), c.width.resize(std::size_t(n));
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    c.centre[i] = column_centre(g, a, int(i));
    c.width[i] = g.plane(a, int(i) + 1) - g.plane(a, int(i));
    const double rc = sum[i] / count[i];
    c.area[i] = count[i] * h * w;
    c.centroid[i] = g.origin[t] + rc;
    c.inertia[i] = w * h * std::max(0.0, sum2[i] - count[i] * rc * rc) + count[i] * w * h * h * h / 12;
  }
  for (std::size_t i = 0; i < sum_w.size(); ++i) c.centroid_w.push_back(g.origin[wa] + sum_w[i] / count[i]);
  // The forces across the axis: the loads, then the reactions (statics).
  std::vector<Force> forces;
  double total = 0, moment = 0;  // sum f, sum s f
  for (const auto& l : loads) {
    const double s = column_centre(g, a, g.coords(l.cell)[a]);
    const double f = (is_positive(l.dir) ? 1 : -1) * l.force;
    forces.push_back({s, f, 0.0});
    total += f, moment += s * f;
  }
  if (c.plan.holding == Holding::Clamp) {
    const double s = c.plan.at[0], r = -total;
    c.reactions[0] = r;
    c.clamp_moment = -(moment + s * r);
    forces.push_back({s, r, c.clamp_moment});
  } else {
    const double s1 = c.plan.at[0], s2 = c.plan.at[1];
    c.reactions[1] = -(moment - s1 * total) / (s2 - s1);
    c.reactions[0] = -total - c.reactions[1];
    forces.push_back({s1, c.reactions[0], 0.0});
    forces.push_back({s2, c.reactions[1], 0.0});
  }
  std::sort(forces.begin(), forces.end(), [](const Force& x, const Force& y) { return x.s < y.s; });
  // One scan: the part of the body below each column's centre (a force at the centre: half on each side).
  c.v.assign(std::size_t(n), 0.0), c.m.assign(std::size_t(n), 0.0), c.n.assign(std::size_t(n), 0.0);
  double f0 = 0, f1 = 0, couples = 0;  // sum f, sum s f, sum of couples below
  std::size_t k = 0;
  for (int i = 0; i < n; ++i) {
    const double s = c.centre[std::size_t(i)];
    for (; k < forces.size() && forces[k].s < s; ++k) f0 += forces[k].f, f1 += forces[k].s * forces[k].f, couples += forces[k].couple;
    double at = 0;
    for (std::size_t e = k; e < forces.size() && forces[e].s == s; ++e) at += forces[e].f;
    c.v[std::size_t(i)] = -f0 - 0.5 * at;
    c.m[std::size_t(i)] = f1 - s * f0 + couples;
  }
  return c;
}

void add_bonded_thrust(Columns& c) {
  if (c.plan.holding != Holding::Supports) return;
  const double s1 = c.plan.at[0], s2 = c.plan.at[1], level = c.plan.support_level;
  auto in_span = [&](std::size_t i) { return c.centre[i] > s1 && c.centre[i] < s2; };
  double num = 0, den = 0;
  for (std::size_t i = 0; i < c.m.size(); ++i)
    if (in_span(i)) {
      const double e = c.centroid[i] - level;
      num += c.m[i] * e / c.inertia[i] * c.width[i];
      den += (1 / c.area[i] + e * e / c.inertia[i]) * c.width[i];
    }
  c.thrust = den > 0 ? -num / den : 0.0;
  for (std::size_t i = 0; i < c.m.size(); ++i)
    if (in_span(i)) c.n[i] = -c.thrust, c.m[i] += (c.centroid[i] - level) * c.thrust;
}

namespace {

/// The columns' agents along `a` (ColumnAgents, column_layers.h).
ColumnAgents column_agents(const Grid& g, int a, int t, int w) {
  const int n = g.cells[a];
  ColumnAgents out;
  auto& start = out.start;
  start.assign(std::size_t(n) + 1, 0);
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell)) ++start[std::size_t(g.coords(cell)[a]) + 1];
  for (int i = 0; i < n; ++i) start[std::size_t(i) + 1] += start[std::size_t(i)];
  std::vector<std::array<int, 2>> key(start.back());  // (t, w) per agent
  out.agents.resize(start.back());
  std::vector<std::size_t> next(start.begin(), start.end() - 1);
  for (std::size_t cell = 0; cell < g.count(); ++cell)
    if (!g.is_air(cell)) {
      const auto c = g.coords(cell);
      const std::size_t k = next[std::size_t(c[a])]++;
      out.agents[k] = cell, key[k] = {c[t], g.dim == 3 ? c[w] : 0};
    }
  // A 3D column's id order runs across w first: sorted by a count over the levels where the column
  // has at least as many agents as levels (linear), else by comparison (a sparse column).
  std::vector<std::size_t> level(std::size_t(g.cells[t]) + 1);
  std::vector<std::pair<std::array<int, 2>, std::size_t>> sorted;
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const std::size_t first = start[i], last = start[i + 1];
    bool in_order = true;
    for (std::size_t k = first + 1; k < last && in_order; ++k) in_order = key[k - 1][0] <= key[k][0];
    if (in_order) continue;
    sorted.resize(last - first);
    if (last - first < std::size_t(g.cells[t])) {
      for (std::size_t k = first; k < last; ++k) sorted[k - first] = {key[k], out.agents[k]};
      std::sort(sorted.begin(), sorted.end());
    } else {
      std::fill(level.begin(), level.end(), 0);
      for (std::size_t k = first; k < last; ++k) ++level[std::size_t(key[k][0]) + 1];
      for (std::size_t j = 1; j < level.size(); ++j) level[j] += level[j - 1];
      for (std::size_t k = first; k < last; ++k) sorted[level[std::size_t(key[k][0])]++] = {key[k], out.agents[k]};
    }
    for (std::size_t k = first; k < last; ++k) key[k] = sorted[k - first].first, out.agents[k] = sorted[k - first].second;
  }
  out.rows.resize(key.size());
  for (std::size_t k = 0; k < key.size(); ++k) out.rows[k] = key[k][0];
  if (g.dim == 3) {
    out.across.resize(key.size());
    for (std::size_t k = 0; k < key.size(); ++k) out.across[k] = key[k][1];
  }
  return out;
}

/// Per agent sigma_a (compressive face forces on its faces across a) and tau_at (Jourawski, one scan
/// down each column, level by level: the agents of equal t, b their width across w); returns each
/// column's shear strain per unit v (the energy mean: int (Q / (I b))^2 dA / G).
std::vector<double> column_stresses(const Grid& g, const Columns& c, const ColumnAgents& ca, double G, TransferResults& out) {
  const int a = c.plan.axis, t = c.plan.across, n = g.cells[a];
  const double h = g.size[t], w = agent_width(g, c.plan.width_axis()), face = g.face_area(a);
  const std::size_t faces = 2 * std::size_t(g.dim), shears = std::size_t(shear_count(g.dim));
  const std::size_t slot = std::size_t(shear_pair(a, t));
  std::vector<double> shear_strain(std::size_t(n), 0.0);
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const double A = c.area[i], rc = c.centroid[i], I = c.inertia[i];
    double above = 0, energy = 0;  // Q of the agents above; int (Q / (I b))^2 dA
    for (std::size_t end = ca.start[i + 1]; end != ca.start[i];) {
      std::size_t begin = end - 1;
      while (begin != ca.start[i] && ca.rows[begin - 1] == ca.rows[end - 1]) --begin;
      if (!c.in_section(i, ca.rows[begin])) {  // beyond the section: carries nothing
        end = begin;
        continue;
      }
      const double b = double(end - begin) * w;  // the section's width at this level
      const double r = g.centre(ca.agents[begin])[t];
      // The first moment of what lies above each level, Q, averaged over the agents' height: the
      // agents above, and this level above the cut (the column's shears then integrate to v exactly).
      const double z1 = r + 0.5 * h - rc, z0 = r - 0.5 * h - rc;
      const double top = above + 0.5 * b * z1 * z1, z3 = z1 * z1 * z1 - z0 * z0 * z0;  // Q = top - b z^2 / 2 in the level
      const double q = top - b * z3 / (6 * h);
      const double sigma = c.n[i] / A + c.m[i] * (r - rc) / I;
      for (std::size_t k = begin; k < end; ++k) {
        const std::size_t cell = ca.agents[k];
        out.faces[cell * faces + std::size_t(direction(a, false))] = out.faces[cell * faces + std::size_t(direction(a, true))] = -sigma * face;
        out.shear[cell * shears + slot] = c.v[i] * q / (I * b);
      }
      // The shear energy's integral of Q^2 over the level, exact (a solid rectangle's k is 5/6).
      const double z5 = z1 * z1 * z1 * z1 * z1 - z0 * z0 * z0 * z0 * z0;
      energy += b * (top * top * h - top * b * z3 / 3 + b * b * z5 / 20) / ((I * b) * (I * b));
      above += h * b * (r - rc);
      end = begin;
    }
    shear_strain[i] = energy / G;
  }
  return shear_strain;
}

/// Flamant's fan (2D and 3D, under a clamp): in each column whose agents extend beyond its core,
/// sigma_a = share (n / A + m (t - c) / I) over every agent of the column, A, c and I weighted by the
/// shares (Columns::weight; the resultants kept), in place of Navier over the 45-degree section; and
/// where a column widens, or a neighbour does, the shear from the equilibrium of the part of each
/// column beyond a cut with its neighbours' (d tau / dt = -d sigma_a / da), which is Jourawski on a
/// prismatic beam and over a widening section a tapered beam's, whose edge carries part of the
/// shear (the corner block's shear changes sign across its height): tau at a cut between two
/// columns is the difference of their force of sigma_a beyond it over the distance of their
/// centres, per the section's width; an agent holds its mean over its height (sigma_a linear in it)
/// and over its one or two neighbours whose agents lie within the column's extent. It integrates
/// to v where m is linear between the centres (n = 0: nothing beyond the lowest face). The plane
/// sections' march keeps the 45-degree section.
void flamant_fan(const Grid& g, const Columns& c, const ColumnAgents& ca, TransferResults& out) {
  const int a = c.plan.axis, t = c.plan.across, n = g.cells[a], rows = g.cells[t];
  std::vector<char> use(std::size_t(n), 0);
  bool any = false;
  for (int i = 0; i < n; ++i) {
    const std::size_t k = std::size_t(i);
    use[k] = c.widens(k) || (i > 0 && c.widens(k - 1)) || (i + 1 < n && c.widens(k + 1));
    any = any || use[k];
  }
  if (!any) return;
  const double h = g.size[t], w = agent_width(g, c.plan.width_axis()), face = g.face_area(a);
  const std::size_t faces = 2 * std::size_t(g.dim), shears = std::size_t(shear_count(g.dim)), slot = std::size_t(shear_pair(a, t));
  const std::size_t levels = std::size_t(rows) + 1;
  // Per column and level: the force of sigma_a beyond the level's lower face, the level's width and
  // its agents' mean force beyond a cut inside them less the faces' mean (b g h^2 / 12, g = share m / I).
  std::vector<double> beyond(std::size_t(n) * levels, 0.0), width(beyond), inside(beyond);
  std::vector<int> low(std::size_t(n), rows), high(std::size_t(n), -1);  // each column's agents' extent
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    double area = 0, first = 0, second = 0;  // the weighted section's sums (positions from the box's side)
    for (std::size_t k = ca.start[i]; k < ca.start[i + 1]; ++k) {
      const double share = c.weight(i, ca.rows[k]), r = g.centre(ca.agents[k])[t] - g.origin[t];
      area += share, first += share * r, second += share * r * r;
    }
    const double rc = first / area, A = area * h * w, I = w * h * std::max(0.0, second - area * rc * rc) + area * w * h * h * h / 12;
    for (std::size_t k = ca.start[i]; k < ca.start[i + 1]; ++k) {
      const std::size_t cell = ca.agents[k], at = i * levels + std::size_t(ca.rows[k]);
      low[i] = std::min(low[i], ca.rows[k]), high[i] = std::max(high[i], ca.rows[k]);
      const double share = c.weight(i, ca.rows[k]), r = g.centre(cell)[t] - g.origin[t];
      if (c.widens(i)) {
        const double sigma = share * (c.n[i] / A + c.m[i] * (r - rc) / I);
        out.faces[cell * faces + std::size_t(direction(a, false))] = out.faces[cell * faces + std::size_t(direction(a, true))] = -sigma * face;
      }
      beyond[at] += -out.faces[cell * faces + std::size_t(direction(a, false))] / face * h * w, width[at] += w;
      inside[at] += share * c.m[i] / I * w * h * h / 12;
    }
    for (std::size_t r = std::size_t(rows); r-- > 0;) beyond[i * levels + r] += beyond[i * levels + r + 1];
  }
  // The change of an agent's mean force beyond a cut from column i to column j, per their distance.
  auto slope = [&](std::size_t i, std::size_t j, std::size_t r) {
    auto mean = [&](std::size_t col) { return 0.5 * (beyond[col * levels + r] + beyond[col * levels + r + 1]) + inside[col * levels + r]; };
    return (mean(j) - mean(i)) / (c.centre[j] - c.centre[i]);
  };
  // A neighbour whose agents reach beyond the column's (the corner beside the foot's first column)
  // holds force beyond every cut of the column: only neighbours within its extent balance its
  // moment (Jourawski where none is).
  auto within = [&](std::size_t j, std::size_t i) { return low[j] >= low[i] && high[j] <= high[i]; };
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const bool before = use[i] && i > 0 && within(i - 1, i), after = use[i] && i + 1 < std::size_t(n) && within(i + 1, i);
    if (!before && !after) continue;
    for (std::size_t k = ca.start[i]; k < ca.start[i + 1]; ++k) {
      const std::size_t r = std::size_t(ca.rows[k]);
      const double sum = (before ? slope(i - 1, i, r) : 0.0) + (after ? slope(i, i + 1, r) : 0.0);
      out.shear[ca.agents[k] * shears + slot] = sum / double(before + after) / width[i * levels + r];
    }
  }
}

/// The plane sections' march over the node lines (planes along a), held by the clamp or the
/// supports: rotation theta, axial displacement U and deflection W at the reference level r0.
struct Sections {
  double r0;
  std::vector<double> theta, U, W;
};

Sections march_sections(const Grid& g, const Material& material, const Columns& c, const std::vector<double>& shear_strain) {
  const int a = c.plan.axis, n = g.cells[a];
  const double E = material.young;
  const double r0 = c.plan.holding == Holding::Supports ? c.plan.support_level
                    : is_positive(c.plan.clamp_side)    ? c.centroid.back()
                                                        : c.centroid.front();
  std::vector<double> theta(std::size_t(n) + 1, 0.0), U(theta), W(theta);
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    const double ds = c.width[i], EI = E * c.inertia[i];
    theta[i + 1] = theta[i] - c.m[i] / EI * ds;
    U[i + 1] = U[i] + (c.n[i] / (E * c.area[i]) + c.m[i] * (r0 - c.centroid[i]) / EI) * ds;
    W[i + 1] = W[i] + (0.5 * (theta[i] + theta[i + 1]) + c.v[i] * shear_strain[i]) * ds;
  }
  // The rigid motion that holds the clamp or the supports: a rotation omega about (s0, r0) and shifts.
  auto at = [&](const std::vector<double>& f, double s) {  // linear between the node lines
    std::size_t i = 0;
    while (i + 1 < std::size_t(n) && g.plane(a, int(i) + 1) <= s) ++i;
    return f[i] + (f[i + 1] - f[i]) * (s - g.plane(a, int(i))) / c.width[i];
  };
  double omega, s0, u0, w0;
  if (c.plan.holding == Holding::Clamp) {
    const std::size_t j = is_positive(c.plan.clamp_side) ? std::size_t(n) : 0;
    omega = -theta[j], s0 = c.plan.at[0], u0 = U[j], w0 = W[j];
  } else {
    const double s1 = c.plan.at[0], s2 = c.plan.at[1];
    omega = -(at(W, s2) - at(W, s1)) / (s2 - s1), s0 = s1, u0 = at(U, s1), w0 = at(W, s1);
  }
  for (std::size_t j = 0; j <= std::size_t(n); ++j)
    theta[j] += omega, U[j] -= u0, W[j] += omega * (g.plane(a, int(j)) - s0) - w0;
  return {r0, std::move(theta), std::move(U), std::move(W)};
}

/// Per node: u_a from the plane section, u_t = W + the Poisson strain -nu sigma_a / E integrated
/// from r0 and, in 3D, u_w = that strain integrated across w from the column's centroid, with u_t's
/// anticlastic part (Saint-Venant's pure bending: no shear strain in the section); each the mean
/// over the columns whose agents share the node.
void node_displacements(const Grid& g, const Material& material, const Columns& c, const ColumnAgents& ca,
                        const Sections& sec, TransferResults& out) {
  const int a = c.plan.axis, t = c.plan.across, wa = c.plan.width_axis(), n = g.cells[a], dim = g.dim;
  const double E = material.young, nu = material.poisson, r0 = sec.r0;
  const std::size_t du = std::size_t(dim);
  std::vector<double> poisson(g.node_count(), 0.0), poisson_w(dim == 3 ? g.node_count() : 0, 0.0);
  std::vector<std::uint8_t> shared(g.node_count(), 0);
  for (std::size_t i = 0; i < std::size_t(n); ++i)
    for (std::size_t k = ca.start[i]; k < ca.start[i + 1]; ++k) {
      const int row = ca.rows[k], col = dim == 3 ? ca.across[k] : 0;
      for (int dl = 0; dl < (dim == 3 ? 2 : 1); ++dl)
        for (int dj = 0; dj < 2; ++dj)
          for (int dk = 0; dk < 2; ++dk) {
            const int line = int(i) + dj, across = row + dk;
            // A node beyond the section moves as the section's nearest edge (the field stays continuous).
            const int held = std::clamp(across, c.first_row[i], c.last_row[i] + 1);
            std::array<int, 3> p{0, 0, 0};
            p[a] = line, p[t] = across, p[wa] = col + dl;
            const std::size_t node = g.node_index(p[0], p[1], p[2]);
            const double r = g.plane(t, held), rc = c.centroid[i];
            const double s = dim == 3 ? g.plane(wa, p[wa]) - c.centroid_w[i] : 0.0;
            const double pt = -nu / E * (c.n[i] / c.area[i] * (r - r0) +
                                         c.m[i] / (2 * c.inertia[i]) * ((r - rc) * (r - rc) - (r0 - rc) * (r0 - rc) - s * s));
            // A node is met more than once in a column (by the agents around it): counted once per column.
            const std::uint8_t bit = std::uint8_t(1u << dj);
            if (shared[node] & bit) continue;
            shared[node] |= bit;
            poisson[node] += pt;
            if (dim == 3) poisson_w[node] += -nu / E * (c.n[i] / c.area[i] + c.m[i] * (r - rc) / c.inertia[i]) * s;
            out.displacement[node * du + std::size_t(a)] = sec.U[std::size_t(line)] - sec.theta[std::size_t(line)] * (r - r0);
            out.displacement[node * du + std::size_t(t)] = sec.W[std::size_t(line)];
          }
      out.diagnostics.agent_updates += 1;
    }
  for (std::size_t node = 0; node < shared.size(); ++node)
    if (shared[node]) {
      const double columns = double((shared[node] & 1) + (shared[node] >> 1));
      out.displacement[node * du + std::size_t(t)] += poisson[node] / columns;
      if (dim == 3) out.displacement[node * du + std::size_t(wa)] = poisson_w[node] / columns;
    }
}

}  // namespace

void column_fields(const Grid& g, const Material& material, const Columns& c, const std::vector<EntryLoad>& loads,
                   TransferResults& out) {
  const int a = c.plan.axis, t = c.plan.across, n = g.cells[a];
  const double E = material.young, nu = material.poisson, G = E / (2 * (1 + nu));
  out.clear_all();
  out.displacement.assign(g.node_count() * std::size_t(g.dim), 0.0);
  auto& d = out.diagnostics;
  const ColumnAgents ca = column_agents(g, a, t, c.plan.width_axis());
  const std::vector<double> shear_strain = column_stresses(g, c, ca, G, out);
  flamant_fan(g, c, ca, out);
  clamp_layer(g, material, c, ca, out);
  clamp_shears(g, c, ca, out);
  load_layer(g, c, ca, loads, out);
  d.agent_updates += ca.agents.size();
  // Generation: columns from the nearest loaded column, in the columns that carry something.
  std::vector<int> reach(std::size_t(n), n + 1);
  for (const auto& l : loads) reach[std::size_t(g.coords(l.cell)[a])] = 0;
  for (int i = 1; i < n; ++i) reach[std::size_t(i)] = std::min(reach[std::size_t(i)], reach[std::size_t(i) - 1] + 1);
  for (int i = n - 2; i >= 0; --i) reach[std::size_t(i)] = std::min(reach[std::size_t(i)], reach[std::size_t(i) + 1] + 1);
  for (std::size_t i = 0; i < std::size_t(n); ++i) {
    if (c.v[i] == 0 && c.m[i] == 0 && c.n[i] == 0) continue;
    for (std::size_t k = ca.start[i]; k < ca.start[i + 1]; ++k) out.generation[ca.agents[k]] = reach[i];
    d.agents_generated += ca.start[i + 1] - ca.start[i];
  }
  node_displacements(g, material, c, ca, march_sections(g, material, c, shear_strain), out);
  for (const auto& l : loads) d.applied += l.force;
  d.rigid_reaction = d.applied;  // every load is carried to the rigid faces by the statics
}

ColumnTransfer::ColumnTransfer(const Grid&, const Material& material) : material_(material) {}

void ColumnTransfer::solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out) {
  if (loads.empty()) return out.clear_all();
  Columns c = column_statics(grid, loads);
  add_bonded_thrust(c);
  column_fields(grid, material_, c, loads, out);
}

}  // namespace agent
