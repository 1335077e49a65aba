// The agent load-transfer sweep (WO2001052193): layer by layer in the load direction.
#include <agent/load_transfer.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace agent {

namespace {
void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}
}  // namespace

LoadTransfer::LoadTransfer(const Grid& grid, Material material, Coefficients k, RuleSet rules)
    : grid_(grid), material_(material), k_(k), rules_(rules) {
  check(grid.dim == 2 || grid.dim == 3, "grid dimension must be 2 or 3");
  check(grid.flags.size() == grid.count(), "grid cells are not set up (use Grid::box)");
  check(material.young > 0 && std::isfinite(material.young), "young must be > 0");
  check(material.poisson > -1 && material.poisson < 0.5, "poisson must be in (-1, 0.5)");
  auto unit = [](double x) { return x >= 0 && x <= 1; };
  check(unit(k.alpha1), "alpha1 must be in [0, 1]");
  check(unit(k.alpha2), "alpha2 must be in [0, 1]");
  check(unit(k.alpha3), "alpha3 must be in [0, 1]");
  check(unit(k.beta), "beta must be in [0, 1]");
  check(unit(k.decay()), "poisson_decay must be in [0, 1]");
  check(k.gamma >= 0 && std::isfinite(k.gamma), "gamma must be >= 0");
  check(rules != RuleSet::Conserving || k.alpha2 + k.alpha3 > 0, "the conserving rule set needs alpha2 + alpha3 > 0");
  if (rules == RuleSet::Directional) check_directional(k.directional);
  faces_.assign(grid.count() * 2 * grid.dim, 0.0);
  generation_.assign(grid.count(), -1);
  std::size_t layer = 0;
  for (int a = 0; a < grid.dim; ++a) layer = std::max(layer, grid.count() / grid.cells[a]);
  fresh_.assign(layer, 0.0);
  down_.assign(layer, 0.0);
  next_down_.assign(layer, 0.0);
  top_.assign(layer, 0.0);
}

std::size_t LoadTransfer::memory_bytes() const {
  return faces_.capacity() * sizeof(double) + generation_.capacity() * sizeof(std::int32_t) + grid_.flags.capacity() +
         (fresh_.capacity() + down_.capacity() + next_down_.capacity() + top_.capacity()) * sizeof(double) +
         touched_.capacity() * sizeof(Touched);
}

void LoadTransfer::clear_touched() {
  const int nd = 2 * grid_.dim;
  for (const auto& t : touched_) {
    const int l0 = t.axis == 0 ? 1 : 0, l1 = t.axis == 2 ? 1 : 2;
    const std::size_t base = std::size_t(t.layer) * grid_.stride(t.axis);
    const std::size_t s0 = grid_.stride(l0), s1 = grid_.stride(l1);
    const int width = t.box.u_hi - t.box.u_lo + 1;
    for (int v = t.box.v_lo; v <= t.box.v_hi; ++v) {
      const std::size_t first = base + t.box.u_lo * s0 + v * s1;
      if (s0 == 1) {  // a contiguous row: one fill each
        std::fill_n(faces_.begin() + first * nd, std::size_t(width) * nd, 0.0);
        std::fill_n(generation_.begin() + first, width, -1);
        continue;
      }
      for (int u = 0; u < width; ++u) {
        std::fill_n(faces_.begin() + (first + u * s0) * nd, nd, 0.0);
        generation_[first + u * s0] = -1;
      }
    }
  }
  touched_.clear();
}

void LoadTransfer::solve(const std::vector<EntryLoad>& loads) {
  for (const auto& load : loads) {
    check(load.cell < grid_.count() && !grid_.is_air(load.cell),
          "entry load outside the body (cell " + std::to_string(load.cell) + ")");
    check(load.dir >= 0 && load.dir < 2 * grid_.dim, "entry load direction out of range");
    check(load.force >= 0 && std::isfinite(load.force), "entry load force must be finite and >= 0");
  }
  clear_touched();
  diagnostics_ = Diagnostics{};
  if (rules_ == RuleSet::Directional) {  // its own marching (agent/directional.h); clears the whole grid
    std::fill(faces_.begin(), faces_.end(), 0.0);
    std::fill(generation_.begin(), generation_.end(), -1);
    return directional_transfer(grid_, k_.directional, k_.gamma, loads, faces_, generation_, diagnostics_);
  }
  for (const auto& load : loads) grid_.dim == 2 ? sweep<2>(load) : sweep<3>(load);
}

template <int Dim>
void LoadTransfer::sweep(const EntryLoad& load) {
  // The dimension is a template parameter so that face offsets are compile-time constants.
  const Grid& g = grid_;
  constexpr int nd = 2 * Dim;
  const int a = axis_of(load.dir);
  const bool forward = is_positive(load.dir);
  const int step = forward ? 1 : -1;
  const int l0 = a == 0 ? 1 : 0, l1 = a == 2 ? 1 : 2;  // the lateral axes (l1 has one cell in 2D)
  const int n0 = g.cells[l0], n1 = g.cells[l1];
  const std::size_t sa = g.stride(a), s0 = g.stride(l0), s1 = g.stride(l1);
  const auto entry = g.coords(load.cell);
  const int eu = entry[l0], ev = entry[l1];
  const int enter_face = direction(a, !forward), exit_face = direction(a, forward);
  const std::ptrdiff_t next_layer = forward ? std::ptrdiff_t(sa) : -std::ptrdiff_t(sa);  // cell offset below
  const bool patent = rules_ == RuleSet::Patent;
  constexpr bool three_d = Dim == 3;
  constexpr int lateral_dirs = three_d ? 4 : 2;
  const double alpha1 = k_.alpha1, alpha2 = k_.alpha2, alpha3 = k_.alpha3, gamma = k_.gamma;
  // Friction: a load from above (or the entry load) is sent to every side with `emit` of it; a
  // friction load travels straight on, passing `carry` of itself to the next agent. The
  // conserving rule set normalises both splits so that nothing is lost.
  const double emit = patent ? alpha3 : alpha3 / (alpha2 + lateral_dirs * alpha3);
  const double carry = patent ? alpha3 : alpha3 / (alpha2 + alpha3);
  const double keep_above = patent ? 0.0 : alpha2 / (alpha2 + lateral_dirs * alpha3);
  const double keep_side = patent ? 0.0 : alpha2 / (alpha2 + alpha3);
  const double decay = k_.decay();
  // Locals, not members, in the hot loops: the compiler cannot keep members in registers
  // across the stores into the face array.
  Diagnostics d;
  double* const faces = faces_.data();
  std::int32_t* const generation = generation_.data();
  const std::uint8_t* const flags = g.flags.data();
  constexpr std::uint8_t air = Grid::kAirBit;
  auto rigid = [flags](std::size_t cell, int side) { return (flags[cell] >> side) & 1; };
  double* const fresh_buf = fresh_.data();
  double* const top_buf = top_.data();

  diagnostics_.applied += load.force;
  if (!(load.force > gamma)) {
    diagnostics_.dropped += load.force;
    return;
  }
  // Generation: the number of agent-to-agent steps from the entry agent (the wavefront in which
  // the sweep reaches it). -1 (unreached) is the largest value as unsigned, so min() keeps the
  // smallest over superposed entries and the comparison counts newly reached agents.
  auto reach = [&](std::size_t cell, int gen) {
    const auto current = std::uint32_t(generation[cell]);
    d.agents_generated += current == UINT32_MAX;
    generation[cell] = std::int32_t(std::min(current, std::uint32_t(gen)));
  };

  // The entry load acts like a load from above (it is sent to the sides with `emit`), except that
  // in the patent reading it enters with alpha1.
  const std::size_t entry_buf = eu + std::size_t(n0) * ev;
  down_[entry_buf] = load.force;
  Box box{eu, eu, ev, ev};
  int layer = entry[a];
  for (int depth = 0;; layer += step, ++depth) {
    const std::size_t layer_base = std::size_t(layer) * sa;
    const bool last_layer = forward ? layer == g.cells[a] - 1 : layer == 0;
    double* const down_buf = down_.data();
    double* const next_down_buf = next_down_.data();
    Box next{INT_MAX, INT_MIN, INT_MAX, INT_MIN};
    Box ext = box;  // grows with friction chains and Poisson pushes

    // Friction chains along one lateral axis, both ways, for one line of the box: inside the box
    // every agent adds `emit` of its load from above; past it a chain runs on until gamma.
    auto friction = [&](int lateral, int n, long cell_stride, long buf_stride, std::size_t first_cell,
                        std::size_t first_buf, int lo, int hi, int& ext_lo, int& ext_hi) {
      // Each way with its direction known at compile time (a generic lambda per way).
      auto run = [&](auto way) {
        constexpr bool up = decltype(way)::value;
        constexpr int sgn = up ? 1 : -1;
        const int end = up ? n : -1;
        double carried = 0;
        int w = up ? lo : hi;
        int last = w;
        auto pass = [&](int w, double out) {
          if (!(out > gamma)) {
            d.dropped += out;
            return 0.0;
          }
          const std::size_t cell = first_cell + w * cell_stride;
          if (w + sgn == end || (flags[cell + sgn * cell_stride] & air)) {  // a boundary face
            if (rigid(cell, direction(lateral, up))) d.rigid_reaction += out;
            else d.passed_out += out;
            return 0.0;
          }
          last = w + sgn;
          return out;
        };
        for (; up ? w <= hi : w >= lo; w += sgn) {
          const std::size_t b = first_buf + w * buf_stride;
          fresh_buf[b] += carried;
          const double out = carry * carried + emit * down_buf[b];
          carried = out == 0 ? 0.0 : pass(w, out);
        }
        for (; carried != 0 && w != end; w += sgn) {
          fresh_buf[first_buf + w * buf_stride] += carried;
          carried = pass(w, carry * carried);
        }
        ext_lo = std::min(ext_lo, last);
        ext_hi = std::max(ext_hi, last);
      };
      run(std::true_type{});
      run(std::false_type{});
    };
    if (alpha3 > 0) {
      for (int v = box.v_lo; v <= box.v_hi; ++v)
        friction(l0, n0, long(s0), 1, layer_base + v * s1, std::size_t(n0) * v, box.u_lo, box.u_hi, ext.u_lo, ext.u_hi);
      if constexpr (three_d)
        for (int u = box.u_lo; u <= box.u_hi; ++u)
          friction(l1, n1, long(s1), n0, layer_base + u * s0, u, box.v_lo, box.v_hi, ext.v_lo, ext.v_hi);
    }

    // Each loaded agent: its entering force, and what it passes on in the load direction.
    const double entry_load = depth == 0 ? load.force : 0.0;
    for (int v = ext.v_lo; v <= ext.v_hi; ++v)
      for (int u = ext.u_lo; u <= ext.u_hi; ++u) {
        const std::size_t b = u + std::size_t(n0) * v;
        const double from_above = down_buf[b], from_side = fresh_buf[b];
        if (from_above == 0 && from_side == 0) continue;
        down_buf[b] = fresh_buf[b] = 0;
        ++d.agent_updates;
        const std::size_t cell = layer_base + u * s0 + v * s1;
        reach(cell, depth + std::abs(u - eu) + std::abs(v - ev));
        double* f = faces + cell * nd;
        double top, down_t;
        if (patent) {
          // Fresh loads (the entry, friction) enter with alpha1.
          top = alpha1 * from_side + from_above;
          if (b == entry_buf && depth == 0) top -= (1 - alpha1) * entry_load;
          down_t = alpha2 * top;
        } else {
          top = from_above + from_side;
          down_t = from_above * keep_above + from_side * keep_side;
        }
        f[enter_face] += top;
        top_buf[b] = top;
        // Tallied here, where it happens: what the agent received less what it passes on, down
        // and (every friction chain arriving goes on with `carry`) to the sides.
        d.lost += from_above + from_side - down_t - (carry * from_side + lateral_dirs * emit * from_above);
        if (!(down_t > gamma)) {
          d.dropped += down_t;
        } else if (!last_layer && !(flags[cell + next_layer] & air)) {
          next_down_buf[b] += down_t;
          f[exit_face] += down_t;
          next.u_lo = std::min(next.u_lo, u);
          next.u_hi = std::max(next.u_hi, u);
          next.v_lo = std::min(next.v_lo, v);
          next.v_hi = std::max(next.v_hi, v);
        } else if (rigid(cell, exit_face)) {
          f[exit_face] += down_t;
          d.rigid_reaction += down_t;
        } else {
          d.passed_out += down_t;
        }
      }

    // Poisson: each squeezed agent pushes its side neighbours with (1 - beta) nu eps A E, which
    // they pass on along the push, decaying by poisson_decay per agent, until it falls to gamma.
    Box touched = ext;
    auto push_line = [&](int lateral, int n, long cell_stride, long buf_stride, std::size_t first_cell,
                         std::size_t first_buf, int lo, int hi, int line_distance, int& reach_lo, int& reach_hi) {
      const double push = (1 - k_.beta) * material_.poisson * g.face_area(lateral) / g.face_area(a);
      const int centre = lateral == l0 ? eu : ev;
      auto run = [&](auto way) {
        constexpr bool up = decltype(way)::value;
        constexpr int sgn = up ? 1 : -1;
        const int face_out = direction(lateral, up), face_in = opposite(face_out);
        const int end = up ? n : -1;
        double carried = 0;
        int w = up ? lo : hi;
        int last = w;
        auto pass = [&](int w, double t) {
          if (!(t > gamma)) {
            d.lateral_dropped += t;
            return 0.0;
          }
          const std::size_t cell = first_cell + w * cell_stride;
          double* f = faces + cell * nd;
          if (w + sgn == end || (flags[cell + sgn * cell_stride] & air)) {  // a rigid face pushes back, a free one lets the push out
            if (rigid(cell, face_out)) {
              f[face_out] += t;
              d.lateral_reaction += t;
            } else {
              d.lateral_passed_out += t;
            }
            return 0.0;
          }
          f[face_out] += t;
          faces[(cell + sgn * cell_stride) * nd + face_in] += t;
          last = w + sgn;
          return t;
        };
        for (; up ? w <= hi : w >= lo; w += sgn) {
          const double t = push * top_buf[first_buf + w * buf_stride] + decay * carried;
          carried = t == 0 ? 0.0 : pass(w, t);
        }
        for (; carried != 0 && w != end; w += sgn) {
          // Past the loaded agents: a push reaching an agent with no load of its own.
          reach(first_cell + w * cell_stride, depth + line_distance + std::abs(w - centre));
          carried = pass(w, decay * carried);
        }
        reach_lo = std::min(reach_lo, last);
        reach_hi = std::max(reach_hi, last);
      };
      run(std::true_type{});
      run(std::false_type{});
    };
    if (k_.beta < 1 && material_.poisson != 0) {
      for (int v = ext.v_lo; v <= ext.v_hi; ++v)
        push_line(l0, n0, long(s0), 1, layer_base + v * s1, std::size_t(n0) * v, ext.u_lo, ext.u_hi, std::abs(v - ev),
                  touched.u_lo, touched.u_hi);
      if constexpr (three_d)
        for (int u = ext.u_lo; u <= ext.u_hi; ++u)
          push_line(l1, n1, long(s1), n0, layer_base + u * s0, u, ext.v_lo, ext.v_hi, std::abs(u - eu), touched.v_lo,
                    touched.v_hi);
    }
    for (int v = ext.v_lo; v <= ext.v_hi; ++v) std::fill_n(top_buf + ext.u_lo + std::size_t(n0) * v, ext.u_hi - ext.u_lo + 1, 0.0);
    touched_.push_back({a, layer, touched});

    if (next.empty()) break;
    box = next;
    std::swap(down_, next_down_);
  }

  diagnostics_.agents_generated += d.agents_generated;
  diagnostics_.agent_updates += d.agent_updates;
  diagnostics_.rigid_reaction += d.rigid_reaction;
  diagnostics_.passed_out += d.passed_out;
  diagnostics_.dropped += d.dropped;
  diagnostics_.lost += d.lost;
  diagnostics_.lateral_reaction += d.lateral_reaction;
  diagnostics_.lateral_passed_out += d.lateral_passed_out;
  diagnostics_.lateral_dropped += d.lateral_dropped;
}

}  // namespace agent
