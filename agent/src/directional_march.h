#pragma once
// What the directional rule set's two path types share (agent/directional.h): the lateral
// positions of the slots, one load's march frame (its axes, faces and per-row steps), the row
// moment balance, and the loop over the loads that hands each load to a path type:
//   TurningPaths (turning_paths.cc)  Paths::Turning: deposited row by row about turning paths;
//   MirrorPaths (mirror_paths.cc)    Paths::Mirror: straight rays mirrored by the free sides.
// A path type is a class template over the slot layout (agent/slots.h) with a constructor
// (Positions, Fan, coefficients, Sinks) and march(frame, load).
#include <agent/directional.h>
#include <agent/slots.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <vector>

namespace agent {
namespace directional {

/// Where a march writes: TransferResults' arrays (shear and balance nullptr when not wanted).
struct Sinks {
  std::vector<double>& faces;
  std::vector<std::int32_t>& generation;
  Diagnostics& d;
  double* shear;
  double* balance;
};

/// Lateral positions are true distances in agents from the box's lower side: slot i starts at
/// at[a][i] (i itself unless a run of empty planes was collapsed into a wider air slot), the box
/// is width[a] agents wide. Packets move, fold and balance the row's moment in these units.
struct Positions {
  explicit Positions(const Grid& grid) : g(&grid) {
    for (int a = 0; a < grid.dim; ++a) {
      // Planes lie on the lattice: rounding gives the whole number of agents exactly.
      auto agents_to = [&](int i) {
        return grid.planes[a].empty() ? double(i) : std::round((grid.plane(a, i) - grid.origin[a]) / grid.size[a]);
      };
      for (int i = 0; i < grid.cells[a]; ++i) at[a].push_back(agents_to(i));
      width[a] = agents_to(grid.cells[a]);
    }
    if (grid.dim == 2) at[2].assign(1, 0.0);
  }
  /// The slot holding lateral position `pos` along axis `a` (clamped to the box).
  int slot_at(int a, double pos) const {
    const int n_a = g->cells[a];
    if (g->planes[a].empty()) return std::min(std::max(int(pos), 0), n_a - 1);
    const int i = int(std::upper_bound(at[a].begin(), at[a].end(), pos) - at[a].begin()) - 1;
    return std::min(std::max(i, 0), n_a - 1);
  }
  const Grid* g;
  std::array<std::vector<double>, 3> at;
  std::array<double, 3> width{1, 1, 1};
};

/// One entry load's march: its axis and direction, lateral axes, faces, and per row the drift of
/// a unit slope and the diffusion step in lateral agents, the packets' side forces and the shear
/// components they write. Slot ids may be Grid::npos on a tiled grid (an unstored tile): air, no
/// rigid face.
template <class Slots>
struct MarchFrame {
  MarchFrame(const Grid& grid, const Slots& layout, const Positions& pos, const DirectionalCoefficients& k,
             const EntryLoad& load)
      : g(grid), slots(layout), dim(grid.dim), nd(2 * grid.dim), a(axis_of(load.dir)), forward(is_positive(load.dir)),
        step(forward ? 1 : -1), l0(lateral_axes(a).l0), l1(lateral_axes(a).l1), n0(grid.cells[l0]), n1(grid.cells[l1]),
        layer_size(std::size_t(n0) * n1), enter_face(direction(a, !forward)), exit_face(direction(a, forward)),
        entry(grid.coords(load.cell)), eu(entry[l0]), ev(entry[l1]), row(grid.size[a]),
        drift_u(row / grid.size[l0]), drift_v(row / grid.size[l1]), spread_m(std::sqrt(k.diffusion_length * row)),
        r_u(spread_m / grid.size[l0]), r_v(spread_m / grid.size[l1]),
        side_u(grid.face_area(l0) / grid.face_area(a)), side_v(dim == 3 ? grid.face_area(l1) / grid.face_area(a) : 0.0),
        at_u(pos.at[l0].data()), at_v(pos.at[l1].data()), tau_sign(forward ? -1.0 : 1.0),
        area_across(grid.face_area(a)), shears(dim == 3 ? 3 : 1), pair_u(shear_pair(a, l0)), pair_v(shear_pair(a, l1)),
        pair_uv(shear_pair(l0, l1)) {}

  const Grid& g;
  const Slots& slots;
  const int dim, nd, a;
  const bool forward;
  const int step, l0, l1, n0, n1;  // l1 has one cell in 2D
  const std::size_t layer_size;
  const int enter_face, exit_face;
  const std::array<int, 3> entry;
  const int eu, ev;
  /// Per row: the drift of a unit slope and the diffusion step, in lateral agents. Diffusion is
  /// a length [m], so the spread at a depth does not depend on the agent size.
  const double row, drift_u, drift_v, spread_m, r_u, r_v;
  /// A packet along a ray carries stress along the ray: sigma_ll = slope_l^2 sigma_aa.
  const double side_u, side_v;
  const double* at_u;
  const double* at_v;
  /// tau_xy of a packet of force F and lateral slope s: the ray's stress -F n n^T / A with n
  /// along (s, -1) for a march down y: +F s / A; marching up (or along +x), -F s / A.
  const double tau_sign, area_across;
  /// The shear components of (march, lateral) in TransferResults::shear: 2D tau_xy; 3D xy, yz, xz.
  const int shears, pair_u, pair_v, pair_uv;

  bool air(std::size_t cell) const { return slots.air(cell); }
  bool rigid(std::size_t cell, int side) const { return slots.rigid(cell, side); }
  /// The slot at a layer and lateral position (agent/slots.h). Loops over a row take its layer's
  /// view once (`here`) and the next layer's (`past`, read only when the row is not the last): a
  /// view per agent cost a tenth of the 3D transfer.
  std::size_t slot_of(int layer, int u, int v) const { return slots.layer(a, layer)(u, v); }
  bool last(int layer) const { return forward ? layer == g.cells[a] - 1 : layer == 0; }
  /// The next row's view (this row's for the last row: then never read).
  auto past(int layer, bool last_layer) const { return slots.layer(a, last_layer ? layer : layer + step); }
  /// Counts `cell` reached at generation `gen` (the smallest over superposed entries).
  void reach(Sinks& out, std::size_t cell, int gen) const {
    const auto current = std::uint32_t(out.generation[cell]);
    out.d.agents_generated += current == UINT32_MAX;
    out.generation[cell] = std::int32_t(std::min(current, std::uint32_t(gen)));
  }
};

/// The row's moment balance (statics of the body above a cut along the row): the force through a
/// row must have its centroid under the load, as in a beam. Packets reflected by a side shift
/// it; a linear, self-equilibrated correction across the row's agents (zero net force, so the
/// load balance is untouched) restores it. It puts the far side in tension, as FEM does.
/// `through`: the packets' force through each agent of the row, zeroed here.
template <class Slots>
void balance_row_moment(const MarchFrame<Slots>& f, int layer, bool last_layer, std::vector<double>& through,
                        Sinks& out) {
  const int n0 = f.n0, n1 = f.n1, exit_face = f.exit_face;
  const double* at_u = f.at_u;
  const double* at_v = f.at_v;
  const auto here = f.slots.layer(f.a, layer), past = f.past(layer, last_layer);
  double count = 0, cu = 0, cv = 0, total = 0, mu = 0, mv = 0;
  bool exits_rigid = true, exits_free = false;  // how the row's agents meet what is past the row
  for (int v = 0; v < n1; ++v)
    for (int u = 0; u < n0; ++u) {
      const std::size_t cell = here(u, v);
      if (f.air(cell)) continue;
      count += 1;
      cu += at_u[u];
      cv += at_v[v];
      const double t = through[u + std::size_t(n0) * v];
      total += t;
      mu += t * (at_u[u] - at_u[f.eu]);
      mv += t * (at_v[v] - at_v[f.ev]);
      const bool exits = last_layer || f.air(past(u, v));
      exits_rigid = exits_rigid && (!exits || f.rigid(cell, exit_face));
      exits_free = exits_free || (exits && !f.rigid(cell, exit_face));
    }
  std::fill(through.begin(), through.end(), 0.0);
  if (count < 2 || total == 0) return;
  cu /= count;
  cv /= count;
  double suu = 0, suv = 0, svv = 0;
  for (int v = 0; v < n1; ++v)
    for (int u = 0; u < n0; ++u)
      if (!f.air(here(u, v))) {
        suu += (at_u[u] - cu) * (at_u[u] - cu);
        suv += (at_u[u] - cu) * (at_v[v] - cv);
        svv += (at_v[v] - cv) * (at_v[v] - cv);
      }
  // delta(u, v) = cu_coef (u - cu) + cv_coef (v - cv) with sum delta (u - eu) = -mu, likewise v.
  double ku = 0, kv = 0;
  if (f.dim == 2 || svv == 0) {
    ku = suu > 0 ? -mu / suu : 0.0;
  } else {
    const double det = suu * svv - suv * suv;
    if (!(std::abs(det) > 0)) return;
    ku = (-mu * svv + mv * suv) / det;
    kv = (-mv * suu + mu * suv) / det;
  }
  if (ku == 0 && kv == 0) return;
  if (out.balance) {  // the slopes alone say it
    double* at_layer = out.balance + 2 * (balance_offset(f.g, f.a) + layer);
    at_layer[0] += ku;
    at_layer[1] += kv;
  }
  for (int v = 0; v < n1; ++v)
    for (int u = 0; u < n0; ++u) {
      const std::size_t cell = here(u, v);
      if (f.air(cell)) continue;
      const double delta = ku * (at_u[u] - cu) + kv * (at_v[v] - cv);
      double* faces = out.faces.data() + cell * f.nd;
      faces[f.enter_face] += delta;
      const bool exits = last_layer || f.air(past(u, v));
      // A boundary face takes it only where the whole row meets one rigid face (net zero there).
      if (!exits) faces[exit_face] += delta;
      else if (exits_rigid && !exits_free) faces[exit_face] += delta;
    }
}

/// Marches every load of `loads` with the path type `PathsOf` (an entry load at or below gamma is
/// dropped whole), over the grid's slot layout.
template <template <class> class PathsOf>
void march_loads(const Grid& grid, const DirectionalCoefficients& k, double gamma, const std::vector<EntryLoad>& loads,
                 Sinks& out) {
  with_slots(grid, [&](const auto& layout) {
    using Slots = std::decay_t<decltype(layout)>;
    const Slots slots = layout;  // a local: its strides and flags stay in registers
    const Positions positions(grid);
    const Fan fan = entry_fan(k, grid.dim);
    PathsOf<Slots> paths(positions, fan, k, out);
    for (const auto& load : loads) {
      out.d.applied += load.force;
      if (!(load.force > gamma)) {
        out.d.dropped += load.force;
        continue;
      }
      paths.march(MarchFrame<Slots>(grid, slots, positions, k, load), load);
    }
  });
}

/// The two path types' marches (Paths::Turning, Paths::Mirror) of `loads` into `out`.
void march_turning(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                   const std::vector<EntryLoad>& loads, Sinks& out);
void march_mirror(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                  const std::vector<EntryLoad>& loads, Sinks& out);

}  // namespace directional
}  // namespace agent
