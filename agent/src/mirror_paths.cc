// The directional rule set's mirror paths (docs/agent-model.md, "Paths"): packets move one row on
// along straight rays at the fan's slopes, diffuse, and are folded back into the box by the free
// sides (a mirror: the slope changes sign); a rigid side absorbs them.
#include "directional_march.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <vector>

namespace agent {
namespace directional {

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

template <class Slots>
class MirrorPaths {
 public:
  MirrorPaths(const Positions& positions, const Fan& fan, const DirectionalCoefficients& k, Sinks& out)
      : pos_(positions), fan_(fan), n_(k.directions), out_(out) {}

  void march(const MarchFrame<Slots>& f, const EntryLoad& load) {
    const int dim = f.dim, directions = dim == 3 ? n_ * n_ : n_;  // 3D: a fan along each lateral axis
    const std::size_t layer_size = f.layer_size;
    row_force_.assign(layer_size, 0.0);  // the packets' force through each agent of a row
    // The rows of packets, reused across the loads (every row is consumed back to zero as it is
    // marched), sized for the largest layer the loads need.
    if (now_.force.size() < directions * layer_size) {
      now_ = Row(directions, layer_size);
      next_ = Row(directions, layer_size);
    }
    const std::size_t entry_slot = f.eu + std::size_t(f.n0) * f.ev;
    for (int dir = 0; dir < directions; ++dir) {
      const double w = fan_.weight[dir % n_] * (dim == 3 ? fan_.weight[dir / n_] : 1.0);
      now_.force[dir * layer_size + entry_slot] = load.force * w;
      now_.box[dir].add(f.eu, f.ev);
    }
    for (int layer = f.entry[f.a], depth = 0;; layer += f.step, ++depth) {
      const bool last_layer = f.last(layer);
      bool any = false;
      for (int dir = 0; dir < directions; ++dir) any |= move_direction(f, dir, layer, depth, last_layer);
      balance_row_moment(f, layer, last_layer, row_force_, out_);
      if (!any) break;
      std::swap(now_, next_);
    }
  }

 private:
  // Moves direction `dir`'s packets of row `layer` onto their agents' faces and one row on (into
  // next_); true if any goes on.
  bool move_direction(const MarchFrame<Slots>& f, int dir, int layer, int depth, bool last_layer) {
    Box& box = now_.box[dir];
    if (box.empty()) return false;
    const int dim = f.dim, n = n_, nd = f.nd, enter_face = f.enter_face, exit_face = f.exit_face, shears = f.shears;
    const int l0 = f.l0, l1 = f.l1;
    const std::size_t layer_size = f.layer_size;
    double* const shear = out_.shear;
    Diagnostics& d = out_.d;
    const int du0 = dir % n, dv0 = dim == 3 ? dir / n : 0;
    const double su = fan_.slope[du0], sv = dim == 3 ? fan_.slope[dv0] : 0.0;
    const double side_force_u = su * su * f.side_u, side_force_v = sv * sv * f.side_v;
    bool any = false;
    for (int v = box.v_lo; v <= box.v_hi; ++v)
      for (int u = box.u_lo; u <= box.u_hi; ++u) {
        const std::size_t slot = dir * layer_size + u + std::size_t(f.n0) * v;
        const double force = now_.force[slot];
        if (force == 0) continue;
        const double off_u = now_.moment_u[slot] / force, off_v = dim == 3 ? now_.moment_v[slot] / force : 0.0;
        now_.force[slot] = now_.moment_u[slot] = now_.moment_v[slot] = 0;
        ++d.packet_moves;
        const std::size_t cell = f.slot_of(layer, u, v);
        f.reach(out_, cell, depth + std::abs(u - f.eu) + std::abs(v - f.ev));
        double* faces = out_.faces.data() + cell * nd;
        faces[enter_face] += force;
        row_force_[u + std::size_t(f.n0) * v] += force;
        if (shear) {
          shear[cell * shears + f.pair_u] += f.tau_sign * force * su / f.area_across;
          if (dim == 3) shear[cell * shears + f.pair_v] += f.tau_sign * force * sv / f.area_across;
        }
        faces[2 * l0] += force * side_force_u;
        faces[2 * l0 + 1] += force * side_force_u;
        if (dim == 3) {
          faces[2 * l1] += force * side_force_v;
          faces[2 * l1 + 1] += force * side_force_v;
        }
        if (last_layer || f.air(f.slot_of(layer + f.step, u, v))) {
          if (f.rigid(cell, exit_face)) {
            faces[exit_face] += force;
            d.rigid_reaction += force;
          } else {
            d.passed_out += force;
          }
          continue;
        }
        faces[exit_face] += force;
        any = true;
        // Move one row on, drift by the slope, and diffuse: two (3D: four) equal pieces
        // at +-r, which adds r^2 of variance per lateral axis exactly.
        const double x = f.at_u[u] + 0.5 + off_u + su * f.drift_u, y = f.at_v[v] + 0.5 + off_v + sv * f.drift_v;
        const double r_u = f.r_u, r_v = f.r_v;
        if (dim == 2) {
          if (r_u == 0) {
            deposit(f, layer, x, y, du0, dv0, force);
          } else {
            deposit(f, layer, x - r_u, y, du0, dv0, 0.5 * force);
            deposit(f, layer, x + r_u, y, du0, dv0, 0.5 * force);
          }
        } else {
          for (int i = 0; i < 4; ++i)
            deposit(f, layer, x + (i & 1 ? r_u : -r_u), y + (i & 2 ? r_v : -r_v), du0, dv0, 0.25 * force);
        }
      }
    box = Box{};
    return any;
  }

  // Folds lateral position `pos` along `lateral` back into the box by the free sides of the row
  // after `layer` (`across`: the slot on the other lateral axis), flipping direction `index`;
  // false if a rigid side takes it.
  bool fold(const MarchFrame<Slots>& f, int layer, double& pos, int lateral, int& index, int across) const {
    const double w = pos_.width[lateral];
    while (pos < 0 || pos > w) {
      const bool low = pos < 0;
      const int side_slot = low ? 0 : f.g.cells[lateral] - 1;
      const std::size_t edge =
          lateral == f.l0 ? f.slot_of(layer + f.step, side_slot, across) : f.slot_of(layer + f.step, across, side_slot);
      if (f.rigid(edge, direction(lateral, !low))) return false;
      pos = low ? -pos : 2.0 * w - pos;
      index = n_ - 1 - index;
    }
    return true;
  }

  // A packet piece arriving at lateral position (x, y) of the row after `layer`, in agents, with
  // direction indices (du, dv): folded back into the box by the free sides, absorbed by a rigid
  // side, passed out where the next row is air.
  void deposit(const MarchFrame<Slots>& f, int layer, double x, double y, int du, int dv, double force) {
    const int iv_guess = pos_.slot_at(f.l1, y);
    if (!fold(f, layer, x, f.l0, du, iv_guess)) {
      out_.d.rigid_reaction += force;
      return;
    }
    const int iu = pos_.slot_at(f.l0, x);
    if (f.dim == 3 && !fold(f, layer, y, f.l1, dv, iu)) {
      out_.d.rigid_reaction += force;
      return;
    }
    const int iv = f.dim == 3 ? pos_.slot_at(f.l1, y) : 0;
    if (f.air(f.slot_of(layer + f.step, iu, iv))) {
      out_.d.passed_out += force;
      return;
    }
    const int dir = du + n_ * dv;
    const std::size_t slot = dir * f.layer_size + iu + std::size_t(f.n0) * iv;
    next_.force[slot] += force;
    next_.moment_u[slot] += force * (x - f.at_u[iu] - 0.5);
    if (f.dim == 3) next_.moment_v[slot] += force * (y - f.at_v[iv] - 0.5);
    next_.box[dir].add(iu, iv);
  }

  const Positions& pos_;
  const Fan& fan_;
  const int n_;  // directions per lateral axis
  Sinks& out_;
  std::vector<double> row_force_;
  Row now_{0, 0}, next_{0, 0};
};

}  // namespace

void march_mirror(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                  const std::vector<EntryLoad>& loads, Sinks& out) {
  march_loads<MirrorPaths>(grid, k, gamma, loads, out);
}

}  // namespace directional
}  // namespace agent
