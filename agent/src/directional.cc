// The directional rule set (the project's extension): load packets with slopes, marched row by row.
#include <agent/directional.h>
#include <agent/slots.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>

namespace agent {

Fan entry_fan(const DirectionalCoefficients& k, int dim) {
  const double power = dim == 3 ? k.fan_power_3d : k.fan_power;
  // Angles evenly spaced over (-fan_angle, fan_angle), none straight down (an even count).
  const double pi = std::acos(-1.0);
  Fan fan;
  double total = 0;
  for (int i = 0; i < k.directions; ++i) {
    const double angle = k.fan_angle * pi / 180 * ((2.0 * i + 1) / k.directions - 1);
    fan.slope.push_back(std::tan(angle));
    fan.weight.push_back(std::pow(std::cos(angle), power));
    total += fan.weight.back();
  }
  for (double& w : fan.weight) w /= total;
  return fan;
}

namespace {

struct Box {
  int u_lo = INT_MAX, u_hi = INT_MIN, v_lo = INT_MAX, v_hi = INT_MIN;
  bool empty() const { return u_lo > u_hi; }
  void add(int u, int v) {
    u_lo = std::min(u_lo, u);
    u_hi = std::max(u_hi, u);
    v_lo = std::min(v_lo, v);
    v_hi = std::max(v_hi, v);
  }
};

/// The packets of one row: per direction and lateral agent, the force and its first moments
/// (force times the offset from the agent's centre, in agents), which keep each packet's
/// position inside its agent when packets of one direction merge.
struct Row {
  std::vector<double> force, moment_u, moment_v;
  std::vector<Box> box;
  Row(std::size_t directions, std::size_t layer)
      : force(directions * layer), moment_u(directions * layer), moment_v(directions * layer), box(directions) {}
};

}  // namespace

namespace {

template <class Slots>
void march(const Grid& g, const Slots& layout, const DirectionalCoefficients& k, double gamma,
           const std::vector<EntryLoad>& loads, std::vector<double>& faces, std::vector<std::int32_t>& generation,
           Diagnostics& d, double* shear, double* balance) {
  const Slots slots = layout;  // a local: its strides and flags stay in registers
  const int dim = g.dim, nd = 2 * dim, n = k.directions;
  const int directions = dim == 3 ? n * n : n;  // 3D: a fan along each lateral axis
  const Fan fan = entry_fan(k, dim);
  // Slot ids may be Grid::npos on a tiled grid (an unstored tile): air, no rigid face.
  auto rigid = [&slots](std::size_t cell, int side) { return slots.rigid(cell, side); };
  auto air = [&slots](std::size_t cell) { return slots.air(cell); };

  Row now(0, 0), next(0, 0);  // mirror paths: sized for the largest layer the loads need
  std::vector<double> row_force;
  // Lateral positions are true distances in agents from the box's lower side: slot i starts at
  // at[a][i] (i itself unless a run of empty planes was collapsed into a wider air slot), the box
  // is width[a] agents wide. Packets move, fold and balance the row's moment in these units.
  std::array<std::vector<double>, 3> at;
  std::array<double, 3> width{1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    // Planes lie on the lattice: rounding gives the whole number of agents exactly.
    auto agents_to = [&](int i) { return g.planes[a].empty() ? double(i) : std::round((g.plane(a, i) - g.origin[a]) / g.size[a]); };
    for (int i = 0; i < g.cells[a]; ++i) at[a].push_back(agents_to(i));
    width[a] = agents_to(g.cells[a]);
  }
  if (dim == 2) at[2].assign(1, 0.0);
  // The slot holding lateral position `pos` along axis `a` (clamped to the box).
  auto slot_at = [&](int a, double pos) {
    const int n_a = g.cells[a];
    if (g.planes[a].empty()) return std::min(std::max(int(pos), 0), n_a - 1);
    const int i = int(std::upper_bound(at[a].begin(), at[a].end(), pos) - at[a].begin()) - 1;
    return std::min(std::max(i, 0), n_a - 1);
  };
  for (const auto& load : loads) {
    d.applied += load.force;
    if (!(load.force > gamma)) {
      d.dropped += load.force;
      continue;
    }
    const int a = axis_of(load.dir);
    const bool forward = is_positive(load.dir);
    const int step = forward ? 1 : -1;
    const int l0 = lateral_axes(a).l0, l1 = lateral_axes(a).l1;  // l1 has one cell in 2D
    const int n0 = g.cells[l0], n1 = g.cells[l1];
    const std::size_t layer_size = std::size_t(n0) * n1;
    const int enter_face = direction(a, !forward), exit_face = direction(a, forward);
    // The slot at a layer and lateral position (agent/slots.h).
    // Loops over a row take its layer's view once (`here`) and the next layer's (`past`, read only
    // when the row is not the last): a view per agent cost a tenth of the 3D transfer.
    auto slot_of = [&](int layer, int u, int v) { return slots.layer(a, layer)(u, v); };
    const auto entry = g.coords(load.cell);
    const int eu = entry[l0], ev = entry[l1];
    // Per row: the drift of a unit slope and the diffusion step, in lateral agents. Diffusion is
    // a length [m], so the spread at a depth does not depend on the agent size.
    const double row = g.size[a];
    const double drift_u = row / g.size[l0], drift_v = row / g.size[l1];
    const double spread_m = std::sqrt(k.diffusion_length * row);
    const double r_u = spread_m / g.size[l0], r_v = spread_m / g.size[l1];
    // A packet along a ray carries stress along the ray: sigma_ll = slope_l^2 sigma_aa.
    const double side_u = g.face_area(l0) / g.face_area(a), side_v = dim == 3 ? g.face_area(l1) / g.face_area(a) : 0.0;

    row_force.assign(layer_size, 0.0);  // the packets' force through each agent of a row

    // The row's moment balance (statics of the body above a cut along the row): the force through a
    // row must have its centroid under the load, as in a beam. Packets reflected by a side shift
    // it; a linear, self-equilibrated correction across the row's agents (zero net force, so the
    // load balance is untouched) restores it. It puts the far side in tension, as FEM does.
    const double* at_u = at[l0].data();
    const double* at_v = at[l1].data();
    auto balance_row_moment = [&](int layer, bool last_layer, std::vector<double>& through) {
      const auto here = slots.layer(a, layer), past = slots.layer(a, last_layer ? layer : layer + step);
      double count = 0, cu = 0, cv = 0, total = 0, mu = 0, mv = 0;
      bool exits_rigid = true, exits_free = false;  // how the row's agents meet what is past the row
      for (int v = 0; v < n1; ++v)
        for (int u = 0; u < n0; ++u) {
          const std::size_t cell = here(u, v);
          if (air(cell)) continue;
          count += 1;
          cu += at_u[u];
          cv += at_v[v];
          const double t = through[u + std::size_t(n0) * v];
          total += t;
          mu += t * (at_u[u] - at_u[eu]);
          mv += t * (at_v[v] - at_v[ev]);
          const bool exits = last_layer || air(past(u, v));
          exits_rigid = exits_rigid && (!exits || rigid(cell, exit_face));
          exits_free = exits_free || (exits && !rigid(cell, exit_face));
        }
      std::fill(through.begin(), through.end(), 0.0);
      if (count < 2 || total == 0) return;
      cu /= count;
      cv /= count;
      double suu = 0, suv = 0, svv = 0;
      for (int v = 0; v < n1; ++v)
        for (int u = 0; u < n0; ++u)
          if (!air(here(u, v))) {
            suu += (at_u[u] - cu) * (at_u[u] - cu);
            suv += (at_u[u] - cu) * (at_v[v] - cv);
            svv += (at_v[v] - cv) * (at_v[v] - cv);
          }
      // delta(u, v) = cu_coef (u - cu) + cv_coef (v - cv) with sum delta (u - eu) = -mu, likewise v.
      double ku = 0, kv = 0;
      if (dim == 2 || svv == 0) {
        ku = suu > 0 ? -mu / suu : 0.0;
      } else {
        const double det = suu * svv - suv * suv;
        if (!(std::abs(det) > 0)) return;
        ku = (-mu * svv + mv * suv) / det;
        kv = (-mv * suu + mu * suv) / det;
      }
      if (ku == 0 && kv == 0) return;
      if (balance) {  // the slopes alone say it
        double* at_layer = balance + 2 * (balance_offset(g, a) + layer);
        at_layer[0] += ku;
        at_layer[1] += kv;
      }
      for (int v = 0; v < n1; ++v)
        for (int u = 0; u < n0; ++u) {
          const std::size_t cell = here(u, v);
          if (air(cell)) continue;
          const double delta = ku * (at_u[u] - cu) + kv * (at_v[v] - cv);
          double* f = faces.data() + cell * nd;
          f[enter_face] += delta;
          const bool exits = last_layer || air(past(u, v));
          // A boundary face takes it only where the whole row meets one rigid face (net zero there).
          if (!exits) f[exit_face] += delta;
          else if (exits_rigid && !exits_free) f[exit_face] += delta;
        }
    };

    // tau_xy of a packet of force F and lateral slope s: the ray's stress -F n n^T / A with n
    // along (s, -1) for a march down y: +F s / A; marching up (or along +x), -F s / A.
    const double tau_sign = forward ? -1.0 : 1.0, area_across = g.face_area(a);
    // The shear components of (march, lateral) in TransferResults::shear: 2D tau_xy; 3D xy, yz, xz.
    const int shears = dim == 3 ? 3 : 1, pair_u = shear_pair(a, l0), pair_v = shear_pair(a, l1),
              pair_uv = shear_pair(l0, l1);
    // Rows of body along the march from `layer` in the entry's column: the depth the paths turn in.
    auto depth_of_body = [&](int layer) {
      int rows = 0;
      for (; layer >= 0 && layer < g.cells[a] && !air(slot_of(layer, eu, ev)); layer += step) ++rows;
      return rows * row;
    };
    // Turning paths (docs/agent-model.md, "Turning paths"): packet k leaves the load at the fan's
    // slope s_k and turns toward its target, the quantile of its weight in the fan mapped onto the
    // body's width on its side: x_k(d) = x0 + L_k tanh(s_k d / L_k). Each row deposits every
    // direction's force as a Gaussian about its path (variance diffusion_length x depth), its tails
    // mirrored at the ends of the row's run of agents and normalised over the run, so each row
    // carries the direction's force exactly. In 3D a packet is a pair of directions, one per lateral
    // axis, its weight and its deposit the product of both axes': a row's force is the product of
    // one distribution per axis (of the runs through the entry's lateral lines). What leaves through
    // a row's exit faces (or lands on air) leaves the load; the rest goes on.
    struct AxisPaths {  // one lateral axis: per direction its turn L_k and what it carries
      int axis = 0, entry = 0;
      double size = 1, x0 = 0;
      std::vector<double> turn, mass;   // 2D: each direction's force; 3D: its weight (x the load's rest)
      std::vector<double> force, shear; // a row's: sum over directions of mass x share (x slope)
      int from = 0, to = -1;            // the agents they cover
    };
    const double root2 = std::sqrt(2.0);
    auto cdf = [root2](double z) { return 0.5 * std::erfc(-z / root2); };
    // The run of agents along lateral axis `which` (0: l0, 1: l1) through (layer, u, v).
    auto run_of = [&](int layer, int which, int u, int v, int& lo, int& hi) {
      auto is_air = [&](int i) { return which == 0 ? air(slot_of(layer, i, v)) : air(slot_of(layer, u, i)); };
      const int n_w = which == 0 ? n0 : n1;
      lo = hi = which == 0 ? u : v;
      while (lo > 0 && !is_air(lo - 1)) --lo;
      while (hi < n_w - 1 && !is_air(hi + 1)) ++hi;
    };
    // 2D: the agent of row `layer` nearest to lateral slot `u` (u itself unless it is air), -1 if the
    // row has none. A path over a hole or a notch goes round it by the nearer side.
    auto nearest_agent = [&](int layer, int u) {
      const auto row_slots = slots.layer(a, layer);
      for (int off = 0; off < n0; ++off) {
        if (u - off >= 0 && !air(row_slots(u - off, 0))) return u - off;
        if (u + off < n0 && !air(row_slots(u + off, 0))) return u + off;
        if (u - off < 0 && u + off >= n0) break;
      }
      return -1;
    };
    // Whether what agent (u, v) of a row carries leaves the body through its exit face (`here`,
    // `past`: the row's slots and the next row's): at the body's last row, at a rigid face, or at a
    // free face when the next row has no agent at all. A free face with body beyond it in the next
    // row (a hole's, a notch's; 2D only: `goes_on`) passes nothing out.
    auto leaves = [&](const auto& here, const auto& past, int u, int v, bool last_layer, bool goes_on) {
      return last_layer || (air(past(u, v)) && (rigid(here(u, v), exit_face) || !goes_on));
    };
    auto march_turning = [&](const EntryLoad& entry_load, double body_depth) {
      std::array<AxisPaths, 2> axes;
      for (int which = 0; which < (dim == 3 ? 2 : 1); ++which) {
        AxisPaths& p = axes[which];
        p.axis = which == 0 ? l0 : l1;
        p.entry = which == 0 ? eu : ev;
        p.size = g.size[p.axis];
        const double* pos = at[p.axis].data();
        p.x0 = (pos[p.entry] + 0.5) * p.size;
        int lo = 0, hi = 0;
        run_of(entry[a], which, eu, ev, lo, hi);
        const double width_low = p.x0 - pos[lo] * p.size, width_high = (pos[hi] + 1) * p.size - p.x0;
        double below = 0;  // the fan's weight of the directions before k
        for (int dir = 0; dir < n; ++dir) {
          const double s = fan.slope[dir], q = below + 0.5 * fan.weight[dir];
          below += fan.weight[dir];
          double L = s < 0 ? -width_low * (1 - 2 * q) : width_high * (2 * q - 1);
          if (!(s * L > 0)) L = std::copysign(1e-9 * p.size, s);  // a target on the wrong side: straight down
          // No farther out than its straight ray reaches at the body's far face (reach 1: not fitted).
          p.turn.push_back(std::copysign(std::min(std::abs(L), std::abs(s) * body_depth), s));
          p.mass.push_back(fan.weight[dir] * (dim == 2 ? entry_load.force : 1.0));
        }
      }
      double rest = dim == 3 ? entry_load.force : 1.0;  // 3D: the load still in the body
      std::vector<double> shares, edge_cdf;  // per agent of a direction's window; per edge
      // Row `layer`'s distribution along one lateral axis. 2D: each direction over the run its path
      // lies in (a path over air: the nearest run), its force leaving where the row's agents exit.
      // 3D: over the run through the entry's lateral line (false if the entry's line is air there).
      auto distribute = [&](AxisPaths& p, int which, int layer, bool last_layer, bool goes_on, double depth_m) {
        const auto here = slots.layer(a, layer), past = slots.layer(a, last_layer ? layer : layer + step);
        const double* pos = at[p.axis].data();
        const double spread = std::max(std::sqrt(k.diffusion_length * depth_m), 0.3 * p.size);
        const int n_w = which == 0 ? n0 : n1;
        int lo = 0, hi = -1;  // the run the paths lie in (2D: the last one found; most paths share it)
        if (dim == 3) {
          if (air(slot_of(layer, eu, ev))) return false;
          run_of(layer, which, eu, ev, lo, hi);
        }
        p.force.assign(std::size_t(n_w), 0.0);
        p.shear.assign(std::size_t(n_w), 0.0);
        p.from = n_w;
        p.to = -1;
        for (int dir = 0; dir < n; ++dir) {
          if (p.mass[dir] == 0) continue;
          const double s = fan.slope[dir], L = p.turn[dir], t = std::tanh(s * depth_m / L);
          double x = p.x0 + L * t;
          const double slope = s * (1 - t * t);
          if (dim == 2) {
            int iu = slot_at(p.axis, x / p.size);
            if (air(here(iu, 0))) iu = nearest_agent(layer, iu);
            if (iu < 0) {  // the body ends under the path
              d.passed_out += p.mass[dir];
              p.mass[dir] = 0;
              continue;
            }
            if (iu < lo || iu > hi) run_of(layer, 0, iu, 0, lo, hi);
          }
          const double edge_lo = pos[lo] * p.size, edge_hi = (pos[hi] + 1) * p.size;
          x = std::min(std::max(x, edge_lo), edge_hi);
          const int from = std::max(lo, slot_at(p.axis, (x - 6 * spread) / p.size));
          const int to = std::min(hi, slot_at(p.axis, (x + 6 * spread) / p.size));
          const int count = to - from + 1;
          // Each agent's share: the Gaussian's mass over it plus its images' (mirrored at the run's
          // ends). A run is agents only, each one agent long (only air slots are wider), so agent
          // i's upper edge is agent i + 1's lower one: the cdf is taken once per edge and image.
          shares.assign(std::size_t(count), 0.0);
          edge_cdf.resize(std::size_t(count) + 1);
          auto edge = [&](int j) { return j < count ? pos[from + j] * p.size : (pos[to] + 1) * p.size; };
          const std::array<double, 3> centres{x, 2 * edge_lo - x, 2 * edge_hi - x};
          for (int image = 0; image < 3; ++image) {
            const double c = centres[image];
            if (image == 0) {
              for (int j = 0; j <= count; ++j) edge_cdf[j] = cdf((edge(j) - c) / spread);
            } else if (image == 1) {
              // The lower image lies below every edge: once its cdf rounds to 1 it stays 1 (adds 0).
              int j = 0;
              for (; j <= count && (j == 0 || edge_cdf[j - 1] < 1.0); ++j) edge_cdf[j] = cdf((edge(j) - c) / spread);
              for (; j <= count; ++j) edge_cdf[j] = 1.0;
            } else {
              // The upper image lies above every edge: below 1e-18 its cdf is dropped, round-off
              // of a direction's force (its shares sum to 1), as the lower image's tail is by 1.
              int j = count;
              for (; j >= 0 && (j == count || edge_cdf[j + 1] >= 1e-18); --j) edge_cdf[j] = cdf((edge(j) - c) / spread);
              for (; j >= 0; --j) edge_cdf[j] = 0.0;
            }
            for (int i = 0; i < count; ++i) shares[i] += edge_cdf[i + 1] - edge_cdf[i];
          }
          double total = 0;
          for (int i = 0; i < count; ++i) total += shares[i];
          if (!(total > 0)) {  // no share at all (the path inside the run has one): its agent
            std::fill(shares.begin(), shares.end(), 0.0);
            shares[std::min(std::max(slot_at(p.axis, x / p.size), from), to) - from] = total = 1;
          }
          double exits = 0;
          for (int i = from; i <= to; ++i) {
            const double m = p.mass[dir] * shares[i - from] / total;
            p.force[i] += m;
            p.shear[i] += m * slope;
            if (dim == 2 && leaves(here, past, i, 0, last_layer, goes_on)) exits += m;
          }
          if (dim == 2) p.mass[dir] = last_layer ? 0.0 : p.mass[dir] - exits;
          p.from = std::min(p.from, from);
          p.to = std::max(p.to, to);
        }
        return true;
      };
      AxisPaths& pu = axes[0];
      AxisPaths& pv = axes[1];
      if (dim == 2) {  // one lateral line: a single agent across l1
        pv.force.assign(1, 1.0);
        pv.shear.assign(1, 0.0);
        pv.from = pv.to = 0;
      }
      for (int layer = entry[a], depth = 0; layer >= 0 && layer < g.cells[a]; layer += step, ++depth) {
        const bool last_layer = forward ? layer == g.cells[a] - 1 : layer == 0;
        const double depth_m = (depth + 0.5) * row;  // of the row's centre below the loaded face
        const bool goes_on = dim == 2 && !last_layer && nearest_agent(layer + step, eu) >= 0;
        if (!distribute(pu, 0, layer, last_layer, goes_on, depth_m) ||
            (dim == 3 && !distribute(pv, 1, layer, last_layer, goes_on, depth_m))) {
          d.passed_out += rest;  // 3D: the body ends under the load's line
          return;
        }
        double left = 0;  // 3D: leaves through the row's exit faces or lands on air
        const auto here = slots.layer(a, layer), past = slots.layer(a, last_layer ? layer : layer + step);
        for (int v = pv.from; v <= pv.to; ++v)
          for (int u = pu.from; u <= pu.to; ++u) {
            const double f_uv = rest * pu.force[u] * pv.force[v];
            if (f_uv == 0) continue;
            const std::size_t cell = here(u, v);
            if (air(cell)) {  // 3D: the body is not a box across the two runs
              left += f_uv;
              d.passed_out += f_uv;
              continue;
            }
            ++d.packet_moves;
            const auto current = std::uint32_t(generation[cell]);
            d.agents_generated += current == UINT32_MAX;
            generation[cell] = std::int32_t(std::min(current, std::uint32_t(depth + std::abs(u - eu) + std::abs(v - ev))));
            double* f = faces.data() + cell * nd;
            f[enter_face] += f_uv;
            row_force[u + std::size_t(n0) * v] += f_uv;
            if (shear) {
              shear[cell * shears + pair_u] += tau_sign * rest * pu.shear[u] * pv.force[v] / area_across;
              if (dim == 3) {
                shear[cell * shears + pair_v] += tau_sign * rest * pu.force[u] * pv.shear[v] / area_across;
                // Across the two lateral axes the ray's stress has -F s_u s_v / A, whichever way it marches.
                shear[cell * shears + pair_uv] -= rest * pu.shear[u] * pv.shear[v] / area_across;
              }
            }
            if (leaves(here, past, u, v, last_layer, goes_on)) {
              left += f_uv;
              if (rigid(cell, exit_face)) {
                f[exit_face] += f_uv;
                d.rigid_reaction += f_uv;
              } else {
                d.passed_out += f_uv;
              }
            } else if (!air(past(u, v))) {
              f[exit_face] += f_uv;
            }  // else a free face with body beyond it in the next row: the load goes round, the face carries none
          }
        if (dim == 3) rest = last_layer ? 0.0 : rest - left;
        balance_row_moment(layer, last_layer, row_force);
        const bool any = dim == 3 ? rest != 0 : std::any_of(pu.mass.begin(), pu.mass.end(), [](double m) { return m != 0; });
        if (!any) break;
      }
    };
    if (k.paths == Paths::Turning) {
      march_turning(load, depth_of_body(entry[a]));
      continue;
    }
    // Mirror paths: the rows of packets, reused across the loads (every row is consumed back to
    // zero as it is marched).
    if (now.force.size() < directions * layer_size) {
      now = Row(directions, layer_size);
      next = Row(directions, layer_size);
    }
    const std::size_t entry_slot = eu + std::size_t(n0) * ev;
    for (int dir = 0; dir < directions; ++dir) {
      const double w = fan.weight[dir % n] * (dim == 3 ? fan.weight[dir / n] : 1.0);
      now.force[dir * layer_size + entry_slot] = load.force * w;
      now.box[dir].add(eu, ev);
    }
    for (int layer = entry[a], depth = 0;; layer += step, ++depth) {
      const bool last_layer = forward ? layer == g.cells[a] - 1 : layer == 0;
      // A packet piece arriving at lateral position (x, y) of the next row, in agents, with
      // direction indices (du, dv): folded back into the box by the free sides (a mirror: the
      // slope changes sign), absorbed by a rigid side, passed out where the next row is air.
      auto deposit = [&](double x, double y, int du, int dv, double force) {
        // `across`: the slot on the other lateral axis.
        auto fold = [&](double& pos, int lateral, int& index, int across) {
          const double w = width[lateral];
          while (pos < 0 || pos > w) {
            const bool low = pos < 0;
            const int side_slot = low ? 0 : g.cells[lateral] - 1;
            const std::size_t edge = lateral == l0 ? slot_of(layer + step, side_slot, across) : slot_of(layer + step, across, side_slot);
            if (rigid(edge, direction(lateral, !low))) return false;
            pos = low ? -pos : 2.0 * w - pos;
            index = n - 1 - index;
          }
          return true;
        };
        const int iv_guess = slot_at(l1, y);
        if (!fold(x, l0, du, iv_guess)) {
          d.rigid_reaction += force;
          return;
        }
        const int iu = slot_at(l0, x);
        if (dim == 3 && !fold(y, l1, dv, iu)) {
          d.rigid_reaction += force;
          return;
        }
        const int iv = dim == 3 ? slot_at(l1, y) : 0;
        if (air(slot_of(layer + step, iu, iv))) {
          d.passed_out += force;
          return;
        }
        const int dir = du + n * dv;
        const std::size_t slot = dir * layer_size + iu + std::size_t(n0) * iv;
        next.force[slot] += force;
        next.moment_u[slot] += force * (x - at_u[iu] - 0.5);
        if (dim == 3) next.moment_v[slot] += force * (y - at_v[iv] - 0.5);
        next.box[dir].add(iu, iv);
      };

      bool any = false;
      for (int dir = 0; dir < directions; ++dir) {
        Box& box = now.box[dir];
        if (box.empty()) continue;
        const int du0 = dir % n, dv0 = dim == 3 ? dir / n : 0;
        const double su = fan.slope[du0], sv = dim == 3 ? fan.slope[dv0] : 0.0;
        const double side_force_u = su * su * side_u, side_force_v = sv * sv * side_v;
        for (int v = box.v_lo; v <= box.v_hi; ++v)
          for (int u = box.u_lo; u <= box.u_hi; ++u) {
            const std::size_t slot = dir * layer_size + u + std::size_t(n0) * v;
            const double force = now.force[slot];
            if (force == 0) continue;
            const double off_u = now.moment_u[slot] / force, off_v = dim == 3 ? now.moment_v[slot] / force : 0.0;
            now.force[slot] = now.moment_u[slot] = now.moment_v[slot] = 0;
            ++d.packet_moves;
            const std::size_t cell = slot_of(layer, u, v);
            const int gen = depth + std::abs(u - eu) + std::abs(v - ev);
            const auto current = std::uint32_t(generation[cell]);
            d.agents_generated += current == UINT32_MAX;
            generation[cell] = std::int32_t(std::min(current, std::uint32_t(gen)));
            double* f = faces.data() + cell * nd;
            f[enter_face] += force;
            row_force[u + std::size_t(n0) * v] += force;
            if (shear) {
              shear[cell * shears + pair_u] += tau_sign * force * su / area_across;
              if (dim == 3) shear[cell * shears + pair_v] += tau_sign * force * sv / area_across;
            }
            f[2 * l0] += force * side_force_u;
            f[2 * l0 + 1] += force * side_force_u;
            if (dim == 3) {
              f[2 * l1] += force * side_force_v;
              f[2 * l1 + 1] += force * side_force_v;
            }
            if (last_layer || air(slot_of(layer + step, u, v))) {
              if (rigid(cell, exit_face)) {
                f[exit_face] += force;
                d.rigid_reaction += force;
              } else {
                d.passed_out += force;
              }
              continue;
            }
            f[exit_face] += force;
            any = true;
            // Move one row on, drift by the slope, and diffuse: two (3D: four) equal pieces
            // at +-r, which adds r^2 of variance per lateral axis exactly.
            const double x = at_u[u] + 0.5 + off_u + su * drift_u, y = at_v[v] + 0.5 + off_v + sv * drift_v;
            if (dim == 2) {
              if (r_u == 0) {
                deposit(x, y, du0, dv0, force);
              } else {
                deposit(x - r_u, y, du0, dv0, 0.5 * force);
                deposit(x + r_u, y, du0, dv0, 0.5 * force);
              }
            } else {
              for (int i = 0; i < 4; ++i)
                deposit(x + (i & 1 ? r_u : -r_u), y + (i & 2 ? r_v : -r_v), du0, dv0, 0.25 * force);
            }
          }
        box = Box{};
      }
      balance_row_moment(layer, last_layer, row_force);
      if (!any) break;
      std::swap(now, next);
    }
  }
}

}  // namespace

void directional_transfer(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                          const std::vector<EntryLoad>& loads, std::vector<double>& faces,
                          std::vector<std::int32_t>& generation, Diagnostics& diagnostics, std::vector<double>& shear,
                          std::vector<double>& balance) {
  with_slots(grid, [&](const auto& slots) {
    march(grid, slots, k, gamma, loads, faces, generation, diagnostics, shear.empty() ? nullptr : shear.data(),
          balance.empty() ? nullptr : balance.data());
  });
}

DirectionalTransfer::DirectionalTransfer(const Coefficients& k) : k_(k) { check_coefficients(k, RuleSet::Directional); }

void DirectionalTransfer::solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out) {
  out.clear_all();
  directional_transfer(grid, k_.directional, k_.gamma, loads, out.faces, out.generation, out.diagnostics, out.shear,
                       out.balance);
}

}  // namespace agent
