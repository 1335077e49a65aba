// The agent load-transfer sweep (WO2001052193): layer by layer in the load direction.
#include <agent/load_transfer.h>

#include <algorithm>
#include <array>
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

// The ids of one row of a tiled grid (agent::Tiles): fixed coordinates on two axes, position u
// along the third; one tile-table read per slot, the rest bit operations.
struct TiledRow {
  const std::uint32_t* number = nullptr;
  std::size_t tile_base = 0, tile_step = 0, local = 0;
  int shift = 0, mask = 0, offset = 0;
  std::size_t operator()(int u) const {
    const std::uint32_t n = number[tile_base + std::size_t(u >> shift) * tile_step];
    if (n == Tiles::kNone) return Grid::npos;
    return (std::size_t(n) << Tiles::kSlotsLog2) | local | (std::size_t(u & mask) << offset);
  }
};

// The row along axis `along` through box coordinates `c` (c[along] ignored).
TiledRow tiled_row(const Grid& g, std::array<int, 3> c, int along) {
  const Tiles& t = g.tiles;
  const std::array<int, 3> offset{0, t.shift[0], t.shift[0] + t.shift[1]};
  const std::array<std::size_t, 3> step{1, std::size_t(t.count[0]), std::size_t(t.count[0]) * t.count[1]};
  c[along] = 0;
  TiledRow r;
  r.number = t.number.data();
  r.tile_step = step[along];
  r.shift = t.shift[along];
  r.mask = (1 << t.shift[along]) - 1;
  r.offset = offset[along];
  for (int x = 0; x < 3; ++x) {
    r.tile_base += std::size_t(c[x] >> t.shift[x]) * step[x];
    r.local |= std::size_t(c[x] & ((1 << t.shift[x]) - 1)) << offset[x];
  }
  return r;
}
}  // namespace

LoadTransfer::LoadTransfer(const Grid& grid, Material material, Coefficients k, RuleSet rules, Readings readings)
    : grid_(grid), material_(material), k_(k), rules_(rules), readings_(readings) {
  check(grid.dim == 2 || grid.dim == 3, "grid dimension must be 2 or 3");
  check(grid.flags.size() == grid.count(), "grid cells are not set up (use Grid::box)");
  check(material.young > 0 && std::isfinite(material.young), "young must be > 0");
  check(material.poisson > -1 && material.poisson < 0.5, "poisson must be in (-1, 0.5)");
  check_coefficients(k, rules);
  if (readings.cyclic()) {
    check(rules == RuleSet::Patent, "readings every_agent_all_operations and boundaries_return are readings of the "
                                    "patent rule set");
    check_cyclic(grid, material, k);
  }
  faces_.assign(grid.count() * 2 * grid.dim, 0.0);
  generation_.assign(grid.count(), -1);
  // One layer of the box across each axis (on tiles too: the scratch is addressed by box position).
  const std::size_t box = std::size_t(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  std::size_t layer = 0;
  for (int a = 0; a < grid.dim; ++a) layer = std::max(layer, box / grid.cells[a]);
  fresh_.assign(layer, 0.0);
  down_.assign(layer, 0.0);
  next_down_.assign(layer, 0.0);
  line_.assign(std::size_t(*std::max_element(grid.cells.begin(), grid.cells.end())), 0.0);
}

std::size_t LoadTransfer::memory_bytes() const {
  return faces_.capacity() * sizeof(double) + generation_.capacity() * sizeof(std::int32_t) + grid_.flags.capacity() +
         (fresh_.capacity() + down_.capacity() + next_down_.capacity() + line_.capacity()) * sizeof(double) +
         (touched_.capacity() + pending_.capacity()) * sizeof(Touched);
}

void LoadTransfer::clear(const Touched& t) {
  const int nd = 2 * grid_.dim;
  const int l0 = t.axis == 0 ? 1 : 0, l1 = t.axis == 2 ? 1 : 2;
  if (grid_.tiled()) {  // slot by slot through the tile table; an unstored tile holds nothing
    std::array<int, 3> c{};
    c[t.axis] = t.layer;
    for (c[l1] = t.box.v_lo; c[l1] <= t.box.v_hi; ++c[l1])
      for (c[l0] = t.box.u_lo; c[l0] <= t.box.u_hi; ++c[l0]) {
        const std::size_t cell = grid_.index(c[0], c[1], c[2]);
        if (cell == Grid::npos) continue;
        std::fill_n(faces_.begin() + cell * nd, nd, 0.0);
        generation_[cell] = -1;
      }
    return;
  }
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

void LoadTransfer::clear_pending(int layer) {
  const auto at = std::equal_range(pending_.begin(), pending_.end(), Touched{0, layer, {}},
                                   [](const Touched& x, const Touched& y) { return x.layer < y.layer; });
  for (auto t = at.first; t != at.second; ++t) {
    clear(*t);
    t->box = Box{1, 0, 1, 0};  // cleared
  }
}

void LoadTransfer::clear_all_pending() {
  for (const auto& t : pending_)
    if (!t.box.empty()) clear(t);
  std::vector<Touched>().swap(pending_);  // held only while a solve clears it
}

void LoadTransfer::solve(const std::vector<EntryLoad>& loads) {
  for (const auto& load : loads) {
    check(load.cell < grid_.count() && !grid_.is_air(load.cell),
          "entry load outside the body (cell " + std::to_string(load.cell) + ")");
    check(load.dir >= 0 && load.dir < 2 * grid_.dim, "entry load direction out of range");
    check(load.force >= 0 && std::isfinite(load.force), "entry load force must be finite and >= 0");
  }
  if (rules_ == RuleSet::Directional) {  // its own marching (agent/directional.h); clears the whole grid
    diagnostics_ = Diagnostics{};
    std::fill(faces_.begin(), faces_.end(), 0.0);
    std::fill(generation_.begin(), generation_.end(), -1);
    return directional_transfer(grid_, k_.directional, k_.gamma, loads, faces_, generation_, diagnostics_);
  }
  if (readings_.cyclic()) {  // readings 2 and 6: a cyclic graph (agent/cyclic_transfer.h); clears the whole grid
    diagnostics_ = Diagnostics{};
    std::fill(faces_.begin(), faces_.end(), 0.0);
    std::fill(generation_.begin(), generation_.end(), -1);
    return cyclic_transfer(grid_, material_, k_, readings_, loads, faces_, generation_, diagnostics_);
  }
  // What the previous solve wrote is cleared. When it was all swept along the first load's axis,
  // the first sweep clears each layer just before it writes there (the layer is then in cache
  // for the sweep instead of passing through memory twice); the rest is cleared after that sweep.
  pending_.swap(touched_);
  touched_.clear();
  const bool lazy = !loads.empty() && std::all_of(pending_.begin(), pending_.end(), [&](const Touched& t) {
    return t.axis == axis_of(loads.front().dir);
  });
  if (lazy)
    std::sort(pending_.begin(), pending_.end(), [](const Touched& x, const Touched& y) { return x.layer < y.layer; });
  else
    clear_all_pending();
  diagnostics_ = Diagnostics{};
  for (const auto& load : loads) {
    if (grid_.tiled())
      grid_.dim == 2 ? sweep<2, true>(load) : sweep<3, true>(load);
    else
      grid_.dim == 2 ? sweep<2, false>(load) : sweep<3, false>(load);
    clear_all_pending();
  }
}

template <int Dim, bool Tiled>
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
  const bool patent = rules_ == RuleSet::Patent;
  const bool once_alpha1 = patent && readings_.non_compounding_entry;  // reading 1
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
  // Ids: dense by strides; on tiles through the tile table (npos: an unstored tile, air).
  // row_at(layer, v): the ids along l0 of a layer's row v; beside(cell, sgn, stride, side):
  // the slot across face `side` (sgn, stride: the dense step); air_at(cell): no agent there.
  auto row_at = [&g, a, l0, l1](int layer, int v) {
    TiledRow row;
    if constexpr (Tiled) {
      std::array<int, 3> c{};
      c[a] = layer;
      c[l1] = v;
      row = tiled_row(g, c, l0);
    }
    return row;
  };
  auto beside = [&g](std::size_t cell, int sgn, long cell_stride, int side) {
    if constexpr (Tiled) return g.neighbour(cell, side);
    else return cell + sgn * cell_stride;
  };
  auto air_at = [flags](std::size_t cell) {
    if constexpr (Tiled)
      if (cell == Grid::npos) return true;
    return (flags[cell] & air) != 0;
  };
  double* const fresh_buf = fresh_.data();
  // Each agent's entering force takes the place of its fresh input once that is consumed.
  double* const top_buf = fresh_buf;
  double* const line = line_.data();

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
    if (!pending_.empty()) clear_pending(layer);  // the previous solve's loads in this layer
    const std::size_t layer_base = std::size_t(layer) * sa;
    const bool last_layer = forward ? layer == g.cells[a] - 1 : layer == 0;
    double* const down_buf = down_.data();
    double* const next_down_buf = next_down_.data();
    Box next{INT_MAX, INT_MIN, INT_MAX, INT_MIN};
    Box ext = box;  // grows with friction chains and Poisson pushes

    // Friction chains run until gamma or a boundary face. friction_pass() settles a chain's load
    // `out` leaving position w (of cell `cell`) toward sgn: dropped, or returned or passed out at a
    // boundary face (then 0), or passed on (then `out`).
    auto friction_pass = [&](int lateral, int sgn, int w, int end, std::size_t cell, long cell_stride, double out,
                             int& reach_end) {
      if (!(out > gamma)) {
        d.dropped += out;
        return 0.0;
      }
      if (w + sgn == end || air_at(beside(cell, sgn, cell_stride, direction(lateral, sgn > 0)))) {  // a boundary face
        if (rigid(cell, direction(lateral, sgn > 0))) d.rigid_reaction += out;
        else d.passed_out += out;
        return 0.0;
      }
      reach_end = sgn > 0 ? std::max(reach_end, w + 1) : std::min(reach_end, w - 1);
      return out;
    };
    if (alpha3 > 0) {
      // Along l0, row by row: the two ways of a row run in lockstep (independent chains, so their
      // latencies overlap; each adds to `fresh` once, and 0 + x + y == 0 + y + x).
      for (int v = box.v_lo; v <= box.v_hi; ++v) {
        const std::size_t row_cell = layer_base + v * s1, row_buf = std::size_t(n0) * v;
        const TiledRow row = row_at(layer, v);
        auto cell_at = [&](int w) {
          if constexpr (Tiled) return row(w);
          else return row_cell + w * s0;
        };
        double up = 0, dn = 0;
        for (int i = 0; i <= box.u_hi - box.u_lo; ++i) {
          const int wu = box.u_lo + i, wd = box.u_hi - i;
          fresh_buf[row_buf + wu] += up;
          fresh_buf[row_buf + wd] += dn;
          const double out_up = carry * up + emit * down_buf[row_buf + wu];
          const double out_dn = carry * dn + emit * down_buf[row_buf + wd];
          up = out_up == 0 ? 0.0 : friction_pass(l0, 1, wu, n0, cell_at(wu), long(s0), out_up, ext.u_hi);
          dn = out_dn == 0 ? 0.0 : friction_pass(l0, -1, wd, -1, cell_at(wd), long(s0), out_dn, ext.u_lo);
        }
        // Past the box, each chain runs on until gamma or a boundary face.
        for (int w = box.u_hi + 1; up != 0 && w != n0; ++w) {
          fresh_buf[row_buf + w] += up;
          up = friction_pass(l0, 1, w, n0, cell_at(w), long(s0), carry * up, ext.u_hi);
        }
        for (int w = box.u_lo - 1; dn != 0 && w != -1; --w) {
          fresh_buf[row_buf + w] += dn;
          dn = friction_pass(l0, -1, w, -1, cell_at(w), long(s0), carry * dn, ext.u_lo);
        }
      }
      // Along l1 (3D), a whole layer plane at once in row order, one chain per column in
      // `line`: memory is read row after row, not one column at a time across the plane.
      if constexpr (three_d) {
        auto columns = [&](auto way) {
          constexpr bool up = decltype(way)::value;
          constexpr int sgn = up ? 1 : -1;
          const int end = up ? n1 : -1;
          int& reach_end = up ? ext.v_hi : ext.v_lo;
          std::fill(line + box.u_lo, line + box.u_hi + 1, 0.0);
          bool running = true;
          for (int v = up ? box.v_lo : box.v_hi; running && v != end; v += sgn) {
            const bool in_box = up ? v <= box.v_hi : v >= box.v_lo;
            const std::size_t row_cell = layer_base + v * s1, row_buf = std::size_t(n0) * v;
            const TiledRow row = row_at(layer, v);
            running = in_box;
            for (int u = box.u_lo; u <= box.u_hi; ++u) {
              double carried = line[u];
              if (!in_box && carried == 0) continue;
              const std::size_t b = row_buf + u;
              fresh_buf[b] += carried;
              const double out = in_box ? carry * carried + emit * down_buf[b] : carry * carried;
              std::size_t cell;
              if constexpr (Tiled) cell = out == 0 ? Grid::npos : row(u);
              else cell = row_cell + u * s0;
              carried = out == 0 ? 0.0 : friction_pass(l1, sgn, v, end, cell, long(s1), out, reach_end);
              line[u] = carried;
              running |= carried != 0;
            }
          }
        };
        columns(std::true_type{});
        columns(std::false_type{});
      }
    }

    // Each loaded agent: its entering force, and what it passes on in the load direction.
    const double entry_load = depth == 0 ? load.force : 0.0;
    for (int v = ext.v_lo; v <= ext.v_hi; ++v) {
      const TiledRow row = row_at(layer, v);
      for (int u = ext.u_lo; u <= ext.u_hi; ++u) {
        const std::size_t b = u + std::size_t(n0) * v;
        const double from_above = down_buf[b], from_side = fresh_buf[b];
        if (from_above == 0 && from_side == 0) continue;
        down_buf[b] = fresh_buf[b] = 0;
        ++d.agent_updates;
        std::size_t cell;
        if constexpr (Tiled) cell = row(u);
        else cell = layer_base + u * s0 + v * s1;
        reach(cell, depth + std::abs(u - eu) + std::abs(v - ev));
        double* f = faces + cell * nd;
        double top, down_t;
        if (once_alpha1) {
          // Reading 1: the entry agent takes P1 = alpha1 P0 and passes P2 = alpha2 P0 on; friction
          // enters whole and goes on with alpha2.
          top = from_side + from_above;
          if (b == entry_buf && depth == 0) top -= (1 - alpha1) * entry_load;
          down_t = alpha2 * (from_side + from_above);
        } else if (patent) {
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
        } else if (!last_layer && !air_at(beside(cell, forward ? 1 : -1, long(sa), exit_face))) {
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
    }

    // Poisson: each squeezed agent pushes its side neighbours with (1 - beta) nu eps A E, which
    // they pass on along the push, decaying by poisson_decay per agent, until it falls to gamma.
    Box touched = ext;
    // push_pass() settles a push `t` leaving position w (of cell `cell`) toward sgn: dropped, or
    // returned by a rigid face / let out by a free one (then 0), or passed on (then t), loading the
    // agent's face and the neighbour's facing face. `deferred`, when given, takes those two loads
    // for later instead (see below).
    auto push_pass = [&](int lateral, int sgn, int w, int end, std::size_t cell, long cell_stride, double t,
                         int& reach_end, double* deferred) {
      if (!(t > gamma)) {
        d.lateral_dropped += t;
        return 0.0;
      }
      const int face_out = direction(lateral, sgn > 0);
      double* f = faces + cell * nd;
      const std::size_t across = w + sgn == end ? Grid::npos : beside(cell, sgn, cell_stride, face_out);
      if (w + sgn == end || air_at(across)) {  // a rigid face pushes back, a free one lets the push out
        if (rigid(cell, face_out)) {
          f[face_out] += t;
          d.lateral_reaction += t;
        } else {
          d.lateral_passed_out += t;
        }
        return 0.0;
      }
      if (deferred) {
        *deferred = t;
      } else {
        f[face_out] += t;
        faces[across * nd + opposite(face_out)] += t;
      }
      reach_end = sgn > 0 ? std::max(reach_end, w + 1) : std::min(reach_end, w - 1);
      return t;
    };
    if (k_.beta < 1 && material_.poisson != 0) {
      const double push0 = (1 - k_.beta) * material_.poisson * g.face_area(l0) / g.face_area(a);
      // Along l0, row by row, the two ways in lockstep. A face between two agents is loaded by
      // both ways; the way down's loads wait in `line` until the way up has loaded every face of
      // the row, so that each face adds its loads in the same order as one way after the other.
      for (int v = ext.v_lo; v <= ext.v_hi; ++v) {
        const std::size_t row_cell = layer_base + v * s1, row_buf = std::size_t(n0) * v;
        const TiledRow row = row_at(layer, v);
        auto cell_at = [&](int w) {
          if constexpr (Tiled) return row(w);
          else return row_cell + w * s0;
        };
        const int line_distance = std::abs(v - ev);
        std::fill(line + ext.u_lo, line + ext.u_hi + 1, 0.0);
        double up = 0, dn = 0;
        for (int i = 0; i <= ext.u_hi - ext.u_lo; ++i) {
          const int wu = ext.u_lo + i, wd = ext.u_hi - i;
          const double t_up = push0 * top_buf[row_buf + wu] + decay * up;
          const double t_dn = push0 * top_buf[row_buf + wd] + decay * dn;
          up = t_up == 0 ? 0.0 : push_pass(l0, 1, wu, n0, cell_at(wu), long(s0), t_up, touched.u_hi, nullptr);
          dn = t_dn == 0 ? 0.0 : push_pass(l0, -1, wd, -1, cell_at(wd), long(s0), t_dn, touched.u_lo, line + wd);
        }
        for (int w = ext.u_lo; w <= ext.u_hi; ++w)
          if (line[w] != 0) {
            const std::size_t cell = cell_at(w);
            faces[cell * nd + direction(l0, false)] += line[w];
            faces[beside(cell, -1, long(s0), direction(l0, false)) * nd + direction(l0, true)] += line[w];
          }
        // Past the loaded agents: a push reaching an agent with no load of its own.
        for (int w = ext.u_hi + 1; up != 0 && w != n0; ++w) {
          const std::size_t cell = cell_at(w);
          reach(cell, depth + line_distance + std::abs(w - eu));
          up = push_pass(l0, 1, w, n0, cell, long(s0), decay * up, touched.u_hi, nullptr);
        }
        for (int w = ext.u_lo - 1; dn != 0 && w != -1; --w) {
          const std::size_t cell = cell_at(w);
          reach(cell, depth + line_distance + std::abs(w - eu));
          dn = push_pass(l0, -1, w, -1, cell, long(s0), decay * dn, touched.u_lo, nullptr);
        }
      }
      // Along l1 (3D), the whole layer plane in row order, one push per column in `line`; the
      // way up over the whole plane before the way down, as each column did before.
      if constexpr (three_d) {
        const double push1 = (1 - k_.beta) * material_.poisson * g.face_area(l1) / g.face_area(a);
        auto columns = [&](auto way) {
          constexpr bool up = decltype(way)::value;
          constexpr int sgn = up ? 1 : -1;
          const int end = up ? n1 : -1;
          int& reach_end = up ? touched.v_hi : touched.v_lo;
          std::fill(line + ext.u_lo, line + ext.u_hi + 1, 0.0);
          bool running = true;
          for (int v = up ? ext.v_lo : ext.v_hi; running && v != end; v += sgn) {
            const bool in_ext = up ? v <= ext.v_hi : v >= ext.v_lo;
            const std::size_t row_cell = layer_base + v * s1, row_buf = std::size_t(n0) * v;
            const TiledRow row = row_at(layer, v);
            running = in_ext;
            for (int u = ext.u_lo; u <= ext.u_hi; ++u) {
              double carried = line[u];
              std::size_t cell;
              if constexpr (Tiled) cell = row(u);
              else cell = row_cell + u * s0;
              if (in_ext) {
                const double t = push1 * top_buf[row_buf + u] + decay * carried;
                carried = t == 0 ? 0.0 : push_pass(l1, sgn, v, end, cell, long(s1), t, reach_end, nullptr);
              } else if (carried != 0) {
                reach(cell, depth + std::abs(u - eu) + std::abs(v - ev));
                carried = push_pass(l1, sgn, v, end, cell, long(s1), decay * carried, reach_end, nullptr);
              }
              line[u] = carried;
              running |= carried != 0;
            }
          }
        };
        columns(std::true_type{});
        columns(std::false_type{});
      }
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
