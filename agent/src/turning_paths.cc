// The directional rule set's turning paths (docs/agent-model.md, "Turning paths"): packet k leaves
// the load at the fan's slope s_k and turns toward its target, the quantile of its weight in the
// fan mapped onto the body's width on its side: x_k(d) = x0 + L_k tanh(s_k d / L_k). Each row
// deposits every direction's force as a Gaussian about its path (variance diffusion_length x
// depth), its tails mirrored at the ends of the row's run of agents and normalised over the run, so
// each row carries the direction's force exactly. In 3D a packet is a pair of directions, one per
// lateral axis, its weight and its deposit the product of both axes': a row's force is the product
// of one distribution per axis (of the runs through the entry's lateral lines), and its shear per
// axis the path's slope plus (3D) the Gaussian's widening. What leaves through a row's exit faces
// (or lands on air) leaves the load; the rest goes on. 2D with near_side = image: both halves of
// the fan map onto the wider side's width, a path that would cross the nearer side folds back as
// its image, and the deposit's images at the run's ends carry the negated slope; near_side =
// blend (the default): each row b(d) = exp(-2 d / W) of each direction on its side path, the rest
// on its image path (docs/agent-model.md, "Loads near a side").
#include "directional_march.h"

#include <agent/exact_functions.h>
#include <agent/normal_cdf.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace agent {
namespace directional {

namespace {

/// The smallest spread of a path's Gaussian, in agents (docs/agent-model.md, "Deposit"): near the
/// loaded face sqrt(diffusion_length x depth) is far below an agent and would put a direction's
/// force on one agent, jumping to the next as the path crosses an edge; at 0.3 agents a path near
/// an edge shares its force with the neighbour (chosen, not fitted).
constexpr double kMinSpreadAgents = 0.3;
/// A path's Gaussian is deposited over the agents within this many spreads of its centre (beyond,
/// 2e-9 of its mass; the shares are normalised over those agents).
constexpr double kSpreadReach = 6;
/// An image's cdf below this is dropped: round-off of a direction's force (its shares sum to 1).
constexpr double kNegligibleCdf = 1e-18;
/// 1 / sqrt(2 pi): the standard normal density at 0.
constexpr double kInvSqrt2Pi = 0.39894228040143267794;
/// A turn whose target lies on the wrong side of the load: this many agents, i.e. straight on.
constexpr double kStraightTurn = 1e-9;
/// near_side = blend: a row at depth d puts exp(-kBlendDecay d / W) of each direction on its side
/// path (W the loaded row's width): the near side's answer gives way to beam statics' over about
/// half the width, as a self-equilibrated end load does in a strip (chosen among five decays on
/// the seed plates, bench/research/near21 in commit 0a2b207; not fitted).
constexpr double kBlendDecay = 2;

/// One lateral axis: per direction its turn L_k and what it carries.
struct AxisPaths {
  int axis = 0, entry = 0;
  double size = 1, x0 = 0;
  double fold_lo = 0, fold_hi = 0;  // 2D: the entry run's ends, where a path's image folds back
  std::vector<double> turn, mass;   // 2D: each direction's force; 3D: its weight (x the load's rest)
  std::vector<double> turn_image;   // 2D, near_side = blend: each direction's turn on the image's width
  std::vector<double> force, shear; // a row's: sum over directions of mass x share (x slope)
  int from = 0, to = -1;            // the agents they cover
};

/// `Cdf`: NormalCdf, or ExactNormalCdf under ExactFunctions.
template <class Slots, class Cdf>
class TurningPaths {
 public:
  TurningPaths(const Positions& positions, const Fan& fan, const DirectionalCoefficients& k, Sinks& out)
      : pos_(positions), fan_(fan), k_(k), out_(out), cdf(Cdf::table()) {}

  void march(const MarchFrame<Slots>& f, const EntryLoad& load) {
    const int dim = f.dim;
    near_side_ = dim == 2 ? k_.near_side : NearSide::Side;
    row_force_.assign(f.layer_size, 0.0);  // the packets' force through each agent of a row
    const double body_depth = depth_of_body(f, f.entry[f.a]);
    std::array<AxisPaths, 2> axes;
    for (int which = 0; which < (dim == 3 ? 2 : 1); ++which) axes[which] = axis_paths(f, which, load, body_depth);
    double rest = dim == 3 ? load.force : 1.0;  // 3D: the load still in the body
    AxisPaths& pu = axes[0];
    AxisPaths& pv = axes[1];
    if (dim == 2) {  // one lateral line: a single agent across l1
      pv.force.assign(1, 1.0);
      pv.shear.assign(1, 0.0);
      pv.from = pv.to = 0;
    }
    for (int layer = f.entry[f.a], depth = 0; layer >= 0 && layer < f.g.cells[f.a]; layer += f.step, ++depth) {
      const bool last_layer = f.last(layer);
      const double depth_m = (depth + 0.5) * f.row;  // of the row's centre below the loaded face
      const bool goes_on = dim == 2 && !last_layer && nearest_agent(f, layer + f.step, f.eu) >= 0;
      if (!distribute(f, pu, 0, layer, last_layer, goes_on, depth_m) ||
          (dim == 3 && !distribute(f, pv, 1, layer, last_layer, goes_on, depth_m))) {
        out_.d.passed_out += rest;  // 3D: the body ends under the load's line
        return;
      }
      const double left = deposit_row(f, pu, pv, rest, layer, depth, last_layer, goes_on);
      if (dim == 3) rest = last_layer ? 0.0 : rest - left;
      balance_row_moment(f, layer, last_layer, row_force_, out_);
      const bool any = dim == 3 ? rest != 0 : std::any_of(pu.mass.begin(), pu.mass.end(), [](double m) { return m != 0; });
      if (!any) break;
    }
  }

 private:
  // Rows of body along the march from `layer` in the entry's column: the depth the paths turn in.
  double depth_of_body(const MarchFrame<Slots>& f, int layer) const {
    int rows = 0;
    for (; layer >= 0 && layer < f.g.cells[f.a] && !f.air(f.slot_of(layer, f.eu, f.ev)); layer += f.step) ++rows;
    return rows * f.row;
  }
  // The run of agents along lateral axis `which` (0: l0, 1: l1) through (layer, u, v).
  void run_of(const MarchFrame<Slots>& f, int layer, int which, int u, int v, int& lo, int& hi) const {
    auto is_air = [&](int i) { return which == 0 ? f.air(f.slot_of(layer, i, v)) : f.air(f.slot_of(layer, u, i)); };
    const int n_w = which == 0 ? f.n0 : f.n1;
    lo = hi = which == 0 ? u : v;
    while (lo > 0 && !is_air(lo - 1)) --lo;
    while (hi < n_w - 1 && !is_air(hi + 1)) ++hi;
  }
  // 2D: the agent of row `layer` nearest to lateral slot `u` (u itself unless it is air), -1 if the
  // row has none. A path over a hole or a notch goes round it by the nearer side.
  int nearest_agent(const MarchFrame<Slots>& f, int layer, int u) const {
    const auto row_slots = f.slots.layer(f.a, layer);
    for (int off = 0; off < f.n0; ++off) {
      if (u - off >= 0 && !f.air(row_slots(u - off, 0))) return u - off;
      if (u + off < f.n0 && !f.air(row_slots(u + off, 0))) return u + off;
      if (u - off < 0 && u + off >= f.n0) break;
    }
    return -1;
  }
  // Whether what agent (u, v) of a row carries leaves the body through its exit face (`here`,
  // `past`: the row's slots and the next row's): at the body's last row, at a rigid face, or at a
  // free face when the next row has no agent at all. A free face with body beyond it in the next
  // row (a hole's, a notch's; 2D only: `goes_on`) passes nothing out.
  template <class Layer>
  static bool leaves(const MarchFrame<Slots>& f, const Layer& here, const Layer& past, int u, int v, bool last_layer,
                     bool goes_on) {
    return last_layer || (f.air(past(u, v)) && (f.rigid(here(u, v), f.exit_face) || !goes_on));
  }

  // Axis `which`'s paths: each direction's turn toward its target and the mass it starts with.
  AxisPaths axis_paths(const MarchFrame<Slots>& f, int which, const EntryLoad& load, double body_depth) const {
    AxisPaths p;
    p.axis = which == 0 ? f.l0 : f.l1;
    p.entry = which == 0 ? f.eu : f.ev;
    p.size = f.g.size[p.axis];
    const double* pos = pos_.at[p.axis].data();
    p.x0 = (pos[p.entry] + 0.5) * p.size;
    int lo = 0, hi = 0;
    run_of(f, f.entry[f.a], which, f.eu, f.ev, lo, hi);
    double width_low = p.x0 - pos[lo] * p.size, width_high = (pos[hi] + 1) * p.size - p.x0;
    p.fold_lo = pos[lo] * p.size;
    p.fold_hi = (pos[hi] + 1) * p.size;
    // near_side = image: both halves of the fan map onto the wider side's width; a path that would
    // cross the nearer side is folded back into the body as its image (distribute). Far below, the
    // force then spreads over the whole width, and the row's balance makes it beam statics' line.
    const double wider = std::max(width_low, width_high);
    if (near_side_ == NearSide::Image) width_low = width_high = wider;
    double below = 0;  // the fan's weight of the directions before k
    for (int dir = 0; dir < k_.directions; ++dir) {
      const double s = fan_.slope[dir], q = below + 0.5 * fan_.weight[dir];
      below += fan_.weight[dir];
      p.turn.push_back(turn(s, q, width_low, width_high, p.size, body_depth));
      if (near_side_ == NearSide::Blend) p.turn_image.push_back(turn(s, q, wider, wider, p.size, body_depth));
      p.mass.push_back(fan_.weight[dir] * (f.dim == 2 ? load.force : 1.0));
    }
    return p;
  }
  // The turn L of a direction of slope s and quantile q toward its target on the widths beside
  // the entry, no farther out than its straight ray reaches at the body's far face (reach 1: not
  // fitted).
  static double turn(double s, double q, double width_low, double width_high, double size, double body_depth) {
    double L = s < 0 ? -width_low * (1 - 2 * q) : width_high * (2 * q - 1);
    if (!(s * L > 0)) L = std::copysign(kStraightTurn * size, s);
    return std::copysign(std::min(std::abs(L), std::abs(s) * body_depth), s);
  }

  // Row `layer`'s distribution along one lateral axis. 2D: each direction over the run its path
  // lies in (a path over air: the nearest run), its force leaving where the row's agents exit.
  // 3D: over the run through the entry's lateral line (false if the entry's line is air there).
  bool distribute(const MarchFrame<Slots>& f, AxisPaths& p, int which, int layer, bool last_layer, bool goes_on,
                  double depth_m) {
    const int dim = f.dim;
    const auto here = f.slots.layer(f.a, layer), past = f.past(layer, last_layer);
    const double spread = std::max(std::sqrt(k_.diffusion_length * depth_m), kMinSpreadAgents * p.size);
    const int n_w = which == 0 ? f.n0 : f.n1;
    int lo = 0, hi = -1;  // the run the paths lie in (2D: the last one found; most paths share it)
    if (dim == 3) {
      if (f.air(f.slot_of(layer, f.eu, f.ev))) return false;
      run_of(f, layer, which, f.eu, f.ev, lo, hi);
    }
    p.force.assign(std::size_t(n_w), 0.0);
    p.shear.assign(std::size_t(n_w), 0.0);
    any_leaving_ = false;
    if (dim == 2) {  // 1 where what an agent carries leaves the body (a factor: no branch per direction)
      leaving_.resize(std::size_t(n_w));
      for (int i = 0; i < n_w; ++i) {
        leaving_[i] = leaves(f, here, past, i, 0, last_layer, goes_on) ? 1.0 : 0.0;
        any_leaving_ = any_leaving_ || leaving_[i] != 0;
      }
    }
    p.from = n_w;
    p.to = -1;
    // near_side = blend: this row's share on the side paths (the rest on the image's)
    const bool blend = near_side_ == NearSide::Blend;
    const double on_side = blend ? std::exp(-kBlendDecay * depth_m / (p.fold_hi - p.fold_lo)) : 1.0;
    for (int dir = 0; dir < k_.directions; ++dir) {
      if (p.mass[dir] == 0) continue;
      double exits = place(f, p, dir, p.turn[dir], on_side, near_side_ == NearSide::Image, layer, spread, depth_m, lo, hi);
      if (exits < 0) {  // the body ends under the path (2D: the row has no agent)
        out_.d.passed_out += p.mass[dir];
        p.mass[dir] = 0;
        continue;
      }
      if (blend) exits += place(f, p, dir, p.turn_image[dir], 1 - on_side, true, layer, spread, depth_m, lo, hi);
      if (dim == 2) p.mass[dir] = last_layer ? 0.0 : p.mass[dir] - exits;
    }
    return true;
  }

  // Deposits `weight` of direction dir's force in row `layer` about its path of turn L (`folded`:
  // the image's path, folded back at the entry run's ends, its deposit's images carrying the
  // negated slope) over the run it lies in (2D: lo..hi, updated; 3D: given); returns what leaves
  // through the row's exit faces (2D), -1 if the row has no agent (2D).
  double place(const MarchFrame<Slots>& f, AxisPaths& p, int dir, double L, double weight, bool folded, int layer,
               double spread, double depth_m, int& lo, int& hi) {
    const int dim = f.dim;
    const double* pos = pos_.at[p.axis].data();
    const double s = fan_.slope[dir], t = std::tanh(s * depth_m / L);
    double x = p.x0 + L * t;
    double slope = s * (1 - t * t);
    if (folded && (x < p.fold_lo || x > p.fold_hi)) {  // the image's path, folded back
      x = x < p.fold_lo ? 2 * p.fold_lo - x : 2 * p.fold_hi - x;
      slope = -slope;
    }
    if (dim == 2) {
      int iu = pos_.slot_at(p.axis, x / p.size);
      if (f.air(f.slot_of(layer, iu, 0))) iu = nearest_agent(f, layer, iu);
      if (iu < 0) return -1;
      if (iu < lo || iu > hi) run_of(f, layer, 0, iu, 0, lo, hi);
    }
    const double edge_lo = pos[lo] * p.size, edge_hi = (pos[hi] + 1) * p.size;
    x = std::min(std::max(x, edge_lo), edge_hi);
    const int from = std::max(lo, pos_.slot_at(p.axis, (x - kSpreadReach * spread) / p.size));
    const int to = std::min(hi, pos_.slot_at(p.axis, (x + kSpreadReach * spread) / p.size));
    const double total = shares_of(p, x, spread, edge_lo, edge_hi, from, to, folded);
    const double scale = weight * p.mass[dir] / total;
    const double exits = deposit(p, scale, slope, from, to, dim == 2, folded);
    if (dim == 3 && spread > kMinSpreadAgents * p.size)  // (at the smallest spread it does not widen)
      add_widening(p, scale, x, spread, edge_lo, edge_hi, from, to, depth_m, f.row);
    p.from = std::min(p.from, from);
    p.to = std::max(p.to, to);
    return exits;
  }

  // Adds a direction's force (`scale` x shares_) and shear (x `slope`) to agents from..to of the
  // row; with `exits`, returns what leaves through their exit faces (leaving_).
  // An image path (`folded`): the shares' part from the run ends' images carries the negated slope
  // (the image's shear cancels the path's at a free side).
  double deposit(AxisPaths& p, double scale, double slope, int from, int to, bool exits, bool folded) {
    const double* share = shares_.data() - from;
    const double* image = folded ? images_.data() - from : nullptr;
    double* force = p.force.data();
    double* shear = p.shear.data();
    double left = 0;
    for (int i = from; i <= to; ++i) {
      const double m = share[i] * scale;
      force[i] += m;
      shear[i] += folded ? (share[i] - 2 * image[i]) * scale * slope : m * slope;
    }
    if (exits && any_leaving_)  // (else every term is 0)
      for (int i = from; i <= to; ++i) left += share[i] * scale * leaving_[i];
    return left;
  }

  // 3D: the shear of the Gaussian's widening (docs/agent-model.md, "Deposit"). Its variance
  // diffusion_length x depth grows with depth, so its mass moves sideways at dx / d(depth) =
  // (x - centre) / (2 depth), which the path's slope does not carry: over agent [a, b] that is
  // int (x - c) N(x; c, sd) dx / (2 depth) = sd (pdf((a - c) / sd) - pdf((b - c) / sd)) / (2 depth),
  // for the Gaussian and its two images (each widens about its own centre, so nothing crosses a
  // run's end). An agent takes the mean of its two faces' 1 / (2 depth); the loaded face carries no
  // shear (the entry row's upper face). Added to the axis's shear as `scale` x that slope.
  void add_widening(AxisPaths& p, double scale, double x, double spread, double edge_lo, double edge_hi, int from,
                    int to, double depth, double row) {
    const double top = depth - 0.5 * row, bottom = depth + 0.5 * row;
    const double rate = 0.5 * ((top > 0.5 * row ? 0.5 / top : 0.0) + 0.5 / bottom);  // entry row: top = 0
    const double* pos = pos_.at[p.axis].data();
    const double first = pos[from] * p.size, last = (pos[to] + 1) * p.size;  // a run: one agent per size
    // the Gaussian and the images within kSpreadReach of the agents (beyond, exp(-18) of its peak)
    double centres[3] = {x, 0, 0};
    int images = 1;
    if (first - (2 * edge_lo - x) < kSpreadReach * spread) centres[images++] = 2 * edge_lo - x;
    if ((2 * edge_hi - x) - last < kSpreadReach * spread) centres[images++] = 2 * edge_hi - x;
    // sd pdf at the edges first + j size, summed over the centres: exp(-z^2 / 2) at z_j = z_0 + j dz
    // by the recurrence e_j+1 = e_j r_j, r_j+1 = r_j exp(-dz^2) (three exponentials per centre)
    const int count = to - from + 1;
    const double dz = p.size / spread;
    edges_.assign(std::size_t(count) + 1, 0.0);
    for (int c = 0; c < images; ++c) {
      const double z0 = (first - centres[c]) / spread, q = std::exp(-dz * dz);
      double e = std::exp(-0.5 * z0 * z0), r = std::exp(-z0 * dz - 0.5 * dz * dz);
      for (int j = 0; j <= count; ++j, e *= r, r *= q) edges_[std::size_t(j)] += e;
    }
    const double factor = scale * rate * kInvSqrt2Pi * spread;
    for (int j = 0; j < count; ++j) p.shear[from + j] += factor * (edges_[std::size_t(j)] - edges_[std::size_t(j) + 1]);
  }

  // Fills shares_ (agents from..to) with each agent's share of a Gaussian of `spread` about x and
  // returns their sum. Each agent's share: the Gaussian's mass over it plus its images' (mirrored at
  // the run's ends). A run is agents only, each one agent long (only air slots are wider), so agent
  // i's upper edge is agent i + 1's lower one, (pos[from] + i + 1) agents up: the cdf is taken once
  // per edge and image. `folded` (an image path): images_ gets the images' part.
  double shares_of(const AxisPaths& p, double x, double spread, double edge_lo, double edge_hi, int from, int to,
                   bool folded) {
    const int count = to - from + 1;
    shares_.resize(std::size_t(count));
    // Edge j at z = z0 + j step, z0 the first edge's (in spreads from the Gaussian's centre)
    const double step = p.size / spread, first = pos_.at[p.axis][from] * step;
    const double z_main = first - x / spread, z_low = first - (2 * edge_lo - x) / spread,
                 z_high = first - (2 * edge_hi - x) / spread;
    // Agent j - 1's share: the cdf at its upper edge j less the last (edges within 6 spreads and
    // an agent, at most 3.4 spreads, of the centre: inside the table), below the centre and above.
    double last = cdf(z_main);
    int j = 1;
    for (; j <= count; ++j) {
      const double z = z_main + j * step;
      if (z > 0) break;
      const double at = cdf.lower(z);
      shares_[j - 1] = at - last;
      last = at;
    }
    for (; j <= count; ++j) {
      const double at = 1 - cdf.lower(-(z_main + j * step));
      shares_[j - 1] = at - last;
      last = at;
    }
    // The lower image lies below every edge: once its cdf rounds to 1 it stays 1 and adds 0, so
    // the agents from there on are skipped.
    if (folded) images_.assign(std::size_t(count), 0.0);
    double below = cdf(z_low);
    for (int j = 1; j <= count && below < 1.0; ++j) {
      const double next = cdf(z_low + j * step);
      shares_[j - 1] += next - below;
      if (folded) images_[j - 1] += next - below;
      below = next;
    }
    // The upper image lies above every edge: a negligible cdf is dropped (taken as 0), as the
    // lower image's tail is by 1; below it every edge's is 0 and adds 0.
    double above = cdf(z_high + count * step);
    j = count - 1;
    for (; j >= 0 && above >= kNegligibleCdf; --j) {
      const double next = cdf(z_high + j * step);
      shares_[j] += above - next;
      if (folded) images_[j] += above - next;
      above = next;
    }
    if (j >= 0) {
      shares_[j] += above;
      if (folded) images_[j] += above;
    }
    double partial[4] = {0, 0, 0, 0};  // four sums, so that the adds do not wait on each other
    int i = 0;
    for (; i + 4 <= count; i += 4)
      for (int k = 0; k < 4; ++k) partial[k] += shares_[i + k];
    for (; i < count; ++i) partial[0] += shares_[i];
    double total = (partial[0] + partial[1]) + (partial[2] + partial[3]);
    if (!(total > 0)) {  // no share at all (the path inside the run has one): its agent
      std::fill(shares_.begin(), shares_.end(), 0.0);
      if (folded) std::fill(images_.begin(), images_.end(), 0.0);
      shares_[std::min(std::max(pos_.slot_at(p.axis, x / p.size), from), to) - from] = total = 1;
    }
    return total;
  }

  // Puts row `layer`'s force (rest x the product of both axes' distributions) on its agents, with
  // the packets' shear, and returns what leaves through the row's exit faces or lands on air (3D).
  double deposit_row(const MarchFrame<Slots>& f, const AxisPaths& pu, const AxisPaths& pv, double rest, int layer,
                     int depth, bool last_layer, bool goes_on) {
    const int dim = f.dim, shears = f.shears, exit_face = f.exit_face;
    double* const shear = out_.shear;
    double left = 0;
    const auto here = f.slots.layer(f.a, layer), past = f.past(layer, last_layer);
    for (int v = pv.from; v <= pv.to; ++v)
      for (int u = pu.from; u <= pu.to; ++u) {
        const double f_uv = rest * pu.force[u] * pv.force[v];
        if (f_uv == 0) continue;
        const std::size_t cell = here(u, v);
        if (f.air(cell)) {  // 3D: the body is not a box across the two runs
          left += f_uv;
          out_.d.passed_out += f_uv;
          continue;
        }
        ++out_.d.packet_moves;
        f.reach(out_, cell, depth + std::abs(u - f.eu) + std::abs(v - f.ev));
        double* faces = out_.faces.data() + cell * f.nd;
        faces[f.enter_face] += f_uv;
        row_force_[u + std::size_t(f.n0) * v] += f_uv;
        if (shear) {
          shear[cell * shears + f.pair_u] += f.tau_sign * rest * pu.shear[u] * pv.force[v] / f.area_across;
          if (dim == 3) {
            shear[cell * shears + f.pair_v] += f.tau_sign * rest * pu.force[u] * pv.shear[v] / f.area_across;
            // Across the two lateral axes the ray's stress has -F s_u s_v / A, whichever way it marches.
            shear[cell * shears + f.pair_uv] -= rest * pu.shear[u] * pv.shear[v] / f.area_across;
          }
        }
        if (leaves(f, here, past, u, v, last_layer, goes_on)) {
          left += f_uv;
          if (f.rigid(cell, exit_face)) {
            faces[exit_face] += f_uv;
            out_.d.rigid_reaction += f_uv;
          } else {
            out_.d.passed_out += f_uv;
          }
        } else if (!f.air(past(u, v))) {
          faces[exit_face] += f_uv;
        }  // else a free face with body beyond it in the next row: the load goes round, the face carries none
      }
    return left;
  }

  const Positions& pos_;
  const Fan& fan_;
  const DirectionalCoefficients& k_;
  Sinks& out_;
  std::vector<double> row_force_;
  std::vector<double> shares_;  // per agent of a direction's window
  std::vector<double> edges_;   // 3D, per edge of a direction's window: its widening's density there
  std::vector<double> images_;  // 2D: the part of shares_ from the run ends' images
  NearSide near_side_ = NearSide::Side;  // 2D: the coefficients' near_side; 3D: side (set by march)
  std::vector<double> leaving_;  // 2D, per agent of the row: 1 where its load leaves the body
  bool any_leaving_ = false;     // 2D: some agent of the row has a 1 in leaving_
  const Cdf& cdf;  // Phi, the deposit's Gaussian's distribution function
};

template <class Slots>
using TablePaths = TurningPaths<Slots, NormalCdf>;
template <class Slots>
using ExactPaths = TurningPaths<Slots, ExactNormalCdf>;

}  // namespace

void march_turning(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                   const std::vector<EntryLoad>& loads, Sinks& out) {
  if (ExactFunctions::active())
    march_loads<ExactPaths>(grid, k, gamma, loads, out);
  else
    march_loads<TablePaths>(grid, k, gamma, loads, out);
}

}  // namespace directional
}  // namespace agent
