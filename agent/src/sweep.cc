// The layer sweep of the patent and conserving rule sets (WO2001052193): layer by layer in the
// load direction. Written once over the slot layout (agent/slots.h) and the rule (a policy below).
#include <agent/slots.h>
#include <agent/sweep.h>

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <stdexcept>
#include <type_traits>
#include <utility>

namespace agent {

namespace {

// The splits of a rule set, per load: friction sends `emit` of a load from above (or the entry
// load) to every side and a friction load goes on with `carry` of itself.
struct Factors {
  double alpha1, alpha2, emit, carry, keep_above, keep_side;
};

// How an agent takes a load from above `above` and a fresh one (the entry, friction) `side`: the
// force on its TOP and what it passes on in the load direction. `entry`: the entry agent of this
// load in its first layer, whose entering load `entry_load` enters with alpha1 in every reading.
struct PatentRule {  // fresh loads enter with alpha1, alpha2 of the TOP goes on
  static Factors factors(const Coefficients& k, int) { return {k.alpha1, k.alpha2, k.alpha3, k.alpha3, 0.0, 0.0}; }
  static void take(const Factors& f, double above, double side, bool entry, double entry_load, double& top,
                   double& down) {
    top = f.alpha1 * side + above;
    if (entry) top -= (1 - f.alpha1) * entry_load;
    down = f.alpha2 * top;
  }
};
// Reading 1: the entry agent takes P1 = alpha1 P0 and passes P2 = alpha2 P0 on; friction enters
// whole and goes on with alpha2.
struct PatentOnceAlpha1Rule {
  static Factors factors(const Coefficients& k, int) { return {k.alpha1, k.alpha2, k.alpha3, k.alpha3, 0.0, 0.0}; }
  static void take(const Factors& f, double above, double side, bool entry, double entry_load, double& top,
                   double& down) {
    top = side + above;
    if (entry) top -= (1 - f.alpha1) * entry_load;
    down = f.alpha2 * (side + above);
  }
};
// The conserving rule set normalises both splits so that nothing is lost.
struct ConservingRule {
  static Factors factors(const Coefficients& k, int lateral_dirs) {
    const double a2 = k.alpha2, a3 = k.alpha3;
    return {1.0, a2, a3 / (a2 + lateral_dirs * a3), a3 / (a2 + a3), a2 / (a2 + lateral_dirs * a3), a2 / (a2 + a3)};
  }
  static void take(const Factors& f, double above, double side, bool, double, double& top, double& down) {
    top = above + side;
    down = above * f.keep_above + side * f.keep_side;
  }
};

}  // namespace

LayerSweep::LayerSweep(const Grid& grid, const Material& material, const Coefficients& k, RuleSet rules,
             const TransferReadings& readings)
    : material_(material), k_(k) {
  check_coefficients(k, rules);
  if (rules != RuleSet::Patent && rules != RuleSet::Conserving)
    throw std::invalid_argument("the layer sweep runs the patent and conserving rule sets");
  if (readings.non_compounding_entry && rules != RuleSet::Patent)
    throw std::invalid_argument("reading non_compounding_entry is a reading of the patent rule set");
  rule_ = rules == RuleSet::Conserving    ? RuleKind::Conserving
          : readings.non_compounding_entry ? RuleKind::PatentOnceAlpha1
                                           : RuleKind::Patent;
  // One layer of the box across each axis (on tiles too: the scratch is addressed by box position).
  const std::size_t box = std::size_t(grid.cells[0]) * grid.cells[1] * grid.cells[2];
  std::size_t layer = 0;
  for (int a = 0; a < grid.dim; ++a) layer = std::max(layer, box / grid.cells[a]);
  fresh_.assign(layer, 0.0);
  down_.assign(layer, 0.0);
  next_down_.assign(layer, 0.0);
  line_.assign(std::size_t(*std::max_element(grid.cells.begin(), grid.cells.end())), 0.0);
}

std::size_t LayerSweep::memory_bytes() const {
  return (fresh_.capacity() + down_.capacity() + next_down_.capacity() + line_.capacity()) * sizeof(double) +
         (touched_.capacity() + pending_.capacity()) * sizeof(Touched);
}

template <class Slots>
void LayerSweep::clear(const Slots& slots, int nd, const Touched& t, TransferResults& out) {
  const auto layer = slots.layer(t.axis, t.layer);
  for (int v = t.box.v_lo; v <= t.box.v_hi; ++v)
    layer.row(v).runs(t.box.u_lo, t.box.u_hi, [&](std::size_t first, std::size_t count) {
      std::fill_n(out.faces.begin() + first * nd, count * nd, 0.0);
      std::fill_n(out.generation.begin() + first, count, -1);
    });
}

template <class Slots>
void LayerSweep::clear_pending(const Slots& slots, int nd, int layer, TransferResults& out) {
  const auto at = std::equal_range(pending_.begin(), pending_.end(), Touched{0, layer, {}},
                                   [](const Touched& x, const Touched& y) { return x.layer < y.layer; });
  for (auto t = at.first; t != at.second; ++t) {
    clear(slots, nd, *t, out);
    t->box = Box{1, 0, 1, 0};  // cleared
  }
}

template <class Slots>
void LayerSweep::clear_all_pending(const Slots& slots, int nd, TransferResults& out) {
  for (const auto& t : pending_)
    if (!t.box.empty()) clear(slots, nd, t, out);
  std::vector<Touched>().swap(pending_);  // held only while a solve clears it
}

void LayerSweep::solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out) {
  // What the previous solve wrote is cleared. When it was all swept along the first load's axis,
  // the first sweep clears each layer just before it writes there (the layer is then in cache
  // for the sweep instead of passing through memory twice); the rest is cleared after that sweep.
  pending_.swap(touched_);
  touched_.clear();
  const bool lazy = !loads.empty() && std::all_of(pending_.begin(), pending_.end(), [&](const Touched& t) {
    return t.axis == axis_of(loads.front().dir);
  });
  with_slots(grid, [&](const auto& slots) {
    if (lazy)
      std::sort(pending_.begin(), pending_.end(), [](const Touched& x, const Touched& y) { return x.layer < y.layer; });
    else
      clear_all_pending(slots, 2 * grid.dim, out);
    out.diagnostics = Diagnostics{};
    for (const auto& load : loads) {
      run(grid, slots, load, out);
      clear_all_pending(slots, 2 * grid.dim, out);
    }
  });
}

template <class Slots>
void LayerSweep::run(const Grid& grid, const Slots& slots, const EntryLoad& load, TransferResults& out) {
  const bool two_d = grid.dim == 2;
  switch (rule_) {
    case RuleKind::Patent:
      return two_d ? layers<2, Slots, PatentRule>(grid, slots, load, out) : layers<3, Slots, PatentRule>(grid, slots, load, out);
    case RuleKind::PatentOnceAlpha1:
      return two_d ? layers<2, Slots, PatentOnceAlpha1Rule>(grid, slots, load, out)
                   : layers<3, Slots, PatentOnceAlpha1Rule>(grid, slots, load, out);
    case RuleKind::Conserving:
      return two_d ? layers<2, Slots, ConservingRule>(grid, slots, load, out)
                   : layers<3, Slots, ConservingRule>(grid, slots, load, out);
  }
}

namespace {

// One load's sweep: the constants every scan of a layer reads, its tallies, and the scans. A local
// of LayerSweep::layers whose scans are each called once and inlined, so that its members stay in
// registers as locals would (a member object that is not a local's cannot: the stores into the
// face array might alias it). Rows run along l0 (lateral_axes); in 3D the lines along l1 are scanned a layer plane at
// a time in row order, one chain per line in `line` (memory read row after row).
template <int Dim, class Slots, class Rule>
struct LoadSweep {
  using Box = LayerSweep::Box;
  static constexpr int nd = 2 * Dim;
  static constexpr bool three_d = Dim == 3;
  static constexpr int lateral_dirs = three_d ? 4 : 2;

  LoadSweep(const Grid& grid, const Slots& layout, const Coefficients& k, const EntryLoad& load, TransferResults& results, double* fresh_scratch, double* line_scratch)
      : g(grid), slots(layout), a(axis_of(load.dir)), forward(is_positive(load.dir)), step(forward ? 1 : -1),
        l0(lateral_axes(a).l0), l1(lateral_axes(a).l1), n0(grid.cells[l0]), n1(grid.cells[l1]),
        entry(grid.coords(load.cell)), eu(entry[l0]), ev(entry[l1]), enter_face(direction(a, !forward)),
        exit_face(direction(a, forward)), alpha3(k.alpha3), gamma(k.gamma), factors(Rule::factors(k, lateral_dirs)),
        emit(factors.emit), carry(factors.carry), decay(k.decay()), faces(results.faces.data()),
        generation(results.generation.data()), lane_a(layout.lane(a)), lane0(layout.lane(l0)), lane1(layout.lane(l1)),
        fresh_buf(fresh_scratch), top_buf(fresh_scratch), line(line_scratch) {}

  const Grid& g;
  const Slots& slots;
  const int a;
  const bool forward;
  const int step, l0, l1, n0, n1;  // l1 has one cell in 2D
  const std::array<int, 3> entry;
  const int eu, ev, enter_face, exit_face;
  const double alpha3, gamma;
  const Factors factors;
  const double emit, carry, decay;
  Diagnostics d;  // this load's, added to the results' at its end
  double* const faces;
  std::int32_t* const generation;
  // Ids of a layer's rows, and the steps across faces along each axis (agent/slots.h).
  const decltype(std::declval<const Slots&>().lane(0)) lane_a, lane0, lane1;
  double* const fresh_buf;
  // Each agent's entering force takes the place of its fresh input once that is consumed.
  double* const top_buf;
  double* const line;

  bool air_at(std::size_t cell) const { return slots.air(cell); }
  bool rigid(std::size_t cell, int side) const { return slots.rigid(cell, side); }

  // Generation: the number of agent-to-agent steps from the entry agent (the wavefront in which
  // the sweep reaches it). -1 (unreached) is the largest value as unsigned, so min() keeps the
  // smallest over superposed entries and the comparison counts newly reached agents.
  void reach(std::size_t cell, int gen) {
    const auto current = std::uint32_t(generation[cell]);
    d.agents_generated += current == UINT32_MAX;
    generation[cell] = std::int32_t(std::min(current, std::uint32_t(gen)));
  }

  // Friction chains run until gamma or a boundary face. friction_pass() settles a chain's load
  // `out` leaving position w (of cell `cell`) toward sgn: dropped, or returned or passed out at a
  // boundary face (then 0), or passed on (then `out`).
  template <class Lane>
  double friction_pass(const Lane& lane, int sgn, int w, int end, std::size_t cell, double out, int& reach_end) {
    if (!(out > gamma)) {
      d.dropped += out;
      return 0.0;
    }
    if (w + sgn == end || air_at(lane.next(cell, sgn))) {  // a boundary face
      if (rigid(cell, direction(lane.axis, sgn > 0))) d.rigid_reaction += out;
      else d.passed_out += out;
      return 0.0;
    }
    reach_end = sgn > 0 ? std::max(reach_end, w + 1) : std::min(reach_end, w - 1);
    return out;
  }

  // Friction along l0, row by row: the two ways of a row run in lockstep (independent chains, so
  // their latencies overlap; each adds to `fresh` once, and 0 + x + y == 0 + y + x).
  template <class Layer>
  void friction_along_rows(const Layer& here, const Box& box, const double* down_buf, Box& ext) {
    for (int v = box.v_lo; v <= box.v_hi; ++v) {
      const std::size_t row_buf = std::size_t(n0) * v;
      const auto cell_at = here.row(v);
      double up = 0, dn = 0;
      for (int i = 0; i <= box.u_hi - box.u_lo; ++i) {
        const int wu = box.u_lo + i, wd = box.u_hi - i;
        fresh_buf[row_buf + wu] += up;
        fresh_buf[row_buf + wd] += dn;
        const double out_up = carry * up + emit * down_buf[row_buf + wu];
        const double out_dn = carry * dn + emit * down_buf[row_buf + wd];
        up = out_up == 0 ? 0.0 : friction_pass(lane0, 1, wu, n0, cell_at(wu), out_up, ext.u_hi);
        dn = out_dn == 0 ? 0.0 : friction_pass(lane0, -1, wd, -1, cell_at(wd), out_dn, ext.u_lo);
      }
      // Past the box, each chain runs on until gamma or a boundary face.
      for (int w = box.u_hi + 1; up != 0 && w != n0; ++w) {
        fresh_buf[row_buf + w] += up;
        up = friction_pass(lane0, 1, w, n0, cell_at(w), carry * up, ext.u_hi);
      }
      for (int w = box.u_lo - 1; dn != 0 && w != -1; --w) {
        fresh_buf[row_buf + w] += dn;
        dn = friction_pass(lane0, -1, w, -1, cell_at(w), carry * dn, ext.u_lo);
      }
    }
  }

  // Friction along l1 (3D) one way (`up`: toward +l1), one chain per line along l1 in `line`.
  template <bool up, class Layer>
  void friction_along_lines(const Layer& here, const Box& box, const double* down_buf, Box& ext) {
    constexpr int sgn = up ? 1 : -1;
    const int end = up ? n1 : -1;
    int& reach_end = up ? ext.v_hi : ext.v_lo;
    std::fill(line + box.u_lo, line + box.u_hi + 1, 0.0);
    bool running = true;
    for (int v = up ? box.v_lo : box.v_hi; running && v != end; v += sgn) {
      const bool in_box = up ? v <= box.v_hi : v >= box.v_lo;
      const std::size_t row_buf = std::size_t(n0) * v;
      const auto row = here.row(v);
      running = in_box;
      for (int u = box.u_lo; u <= box.u_hi; ++u) {
        double carried = line[u];
        if (!in_box && carried == 0) continue;
        const std::size_t b = row_buf + u;
        fresh_buf[b] += carried;
        const double out = in_box ? carry * carried + emit * down_buf[b] : carry * carried;
        carried = out == 0 ? 0.0 : friction_pass(lane1, sgn, v, end, row(u), out, reach_end);
        line[u] = carried;
        running |= carried != 0;
      }
    }
  }

  // Each loaded agent of the layer (within `ext`): its entering force, and what it passes on in
  // the load direction (into `next_down_buf`, widening `next`).
  template <class Layer>
  void take_loads(const Layer& here, int depth, bool last_layer, bool entry_layer, double entry_load, const Box& ext,
                  double* down_buf, double* next_down_buf, Box& next) {
    const std::size_t entry_buf = eu + std::size_t(n0) * ev;
    for (int v = ext.v_lo; v <= ext.v_hi; ++v) {
      const auto row = here.row(v);
      for (int u = ext.u_lo; u <= ext.u_hi; ++u) {
        const std::size_t b = u + std::size_t(n0) * v;
        const double from_above = down_buf[b], from_side = fresh_buf[b];
        if (from_above == 0 && from_side == 0) continue;
        down_buf[b] = fresh_buf[b] = 0;
        ++d.agent_updates;
        const std::size_t cell = row(u);
        reach(cell, depth + std::abs(u - eu) + std::abs(v - ev));
        double* f = faces + cell * nd;
        double top, down_t;
        Rule::take(factors, from_above, from_side, b == entry_buf && entry_layer, entry_load, top, down_t);
        f[enter_face] += top;
        top_buf[b] = top;
        // Tallied here, where it happens: what the agent received less what it passes on, down
        // and (every friction chain arriving goes on with `carry`) to the sides.
        d.lost += from_above + from_side - down_t - (carry * from_side + lateral_dirs * emit * from_above);
        if (!(down_t > gamma)) {
          d.dropped += down_t;
        } else if (!last_layer && !air_at(lane_a.next(cell, step))) {
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
  }

  // push_pass() settles a push `t` leaving position w (of cell `cell`) toward sgn: dropped, or
  // returned by a rigid face / let out by a free one (then 0), or passed on (then t), loading the
  // agent's face and the neighbour's facing face. `deferred`, when given, takes those two loads
  // for later instead (see push_along_rows).
  template <class Lane>
  double push_pass(const Lane& lane, int sgn, int w, int end, std::size_t cell, double t, int& reach_end,
                   double* deferred) {
    if (!(t > gamma)) {
      d.lateral_dropped += t;
      return 0.0;
    }
    const int face_out = direction(lane.axis, sgn > 0);
    double* f = faces + cell * nd;
    const std::size_t across = w + sgn == end ? Grid::npos : lane.next(cell, sgn);
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
  }

  // Pushes along l0, row by row, the two ways in lockstep. A face between two agents is loaded by
  // both ways; the way down's loads wait in `line` until the way up has loaded every face of the
  // row, so that each face adds its loads in the same order as one way after the other.
  template <class Layer>
  void push_along_rows(const Layer& here, int depth, double push0, const Box& ext, Box& touched) {
    for (int v = ext.v_lo; v <= ext.v_hi; ++v) {
      const std::size_t row_buf = std::size_t(n0) * v;
      const auto cell_at = here.row(v);
      const int line_distance = std::abs(v - ev);
      std::fill(line + ext.u_lo, line + ext.u_hi + 1, 0.0);
      double up = 0, dn = 0;
      for (int i = 0; i <= ext.u_hi - ext.u_lo; ++i) {
        const int wu = ext.u_lo + i, wd = ext.u_hi - i;
        const double t_up = push0 * top_buf[row_buf + wu] + decay * up;
        const double t_dn = push0 * top_buf[row_buf + wd] + decay * dn;
        up = t_up == 0 ? 0.0 : push_pass(lane0, 1, wu, n0, cell_at(wu), t_up, touched.u_hi, nullptr);
        dn = t_dn == 0 ? 0.0 : push_pass(lane0, -1, wd, -1, cell_at(wd), t_dn, touched.u_lo, line + wd);
      }
      for (int w = ext.u_lo; w <= ext.u_hi; ++w)
        if (line[w] != 0) {
          const std::size_t cell = cell_at(w);
          faces[cell * nd + direction(l0, false)] += line[w];
          faces[lane0.next(cell, -1) * nd + direction(l0, true)] += line[w];
        }
      // Past the loaded agents: a push reaching an agent with no load of its own.
      for (int w = ext.u_hi + 1; up != 0 && w != n0; ++w) {
        const std::size_t cell = cell_at(w);
        reach(cell, depth + line_distance + std::abs(w - eu));
        up = push_pass(lane0, 1, w, n0, cell, decay * up, touched.u_hi, nullptr);
      }
      for (int w = ext.u_lo - 1; dn != 0 && w != -1; --w) {
        const std::size_t cell = cell_at(w);
        reach(cell, depth + line_distance + std::abs(w - eu));
        dn = push_pass(lane0, -1, w, -1, cell, decay * dn, touched.u_lo, nullptr);
      }
    }
  }

  // Pushes along l1 (3D) one way, one push per line along l1 in `line`; the way up over the whole
  // plane before the way down, as each line did when scanned alone.
  template <bool up, class Layer>
  void push_along_lines(const Layer& here, int depth, double push1, const Box& ext, Box& touched) {
    constexpr int sgn = up ? 1 : -1;
    const int end = up ? n1 : -1;
    int& reach_end = up ? touched.v_hi : touched.v_lo;
    std::fill(line + ext.u_lo, line + ext.u_hi + 1, 0.0);
    bool running = true;
    for (int v = up ? ext.v_lo : ext.v_hi; running && v != end; v += sgn) {
      const bool in_ext = up ? v <= ext.v_hi : v >= ext.v_lo;
      const std::size_t row_buf = std::size_t(n0) * v;
      const auto row = here.row(v);
      running = in_ext;
      for (int u = ext.u_lo; u <= ext.u_hi; ++u) {
        double carried = line[u];
        const std::size_t cell = row(u);
        if (in_ext) {
          const double t = push1 * top_buf[row_buf + u] + decay * carried;
          carried = t == 0 ? 0.0 : push_pass(lane1, sgn, v, end, cell, t, reach_end, nullptr);
        } else if (carried != 0) {
          reach(cell, depth + std::abs(u - eu) + std::abs(v - ev));
          carried = push_pass(lane1, sgn, v, end, cell, decay * carried, reach_end, nullptr);
        }
        line[u] = carried;
        running |= carried != 0;
      }
    }
  }
};

}  // namespace

template <int Dim, class Slots, class Rule>
void LayerSweep::layers(const Grid& g, const Slots& layout, const EntryLoad& load, TransferResults& results) {
  // The dimension is a template parameter so that face offsets are compile-time constants.
  const Slots slots = layout;  // a local: its strides and flags stay in registers
  // One load's sweep, a local: its constants and its tallies (held by value: a reference to a
  // Diagnostics elsewhere cost the 2D sweep 5-10 %) stay in registers across the face stores.
  LoadSweep<Dim, Slots, Rule> s(g, slots, k_, load, results, fresh_.data(), line_.data());
  const int a = s.a, step = s.step, n0 = s.n0;
  Diagnostics& total = results.diagnostics;

  total.applied += load.force;
  if (!(load.force > s.gamma)) {
    total.dropped += load.force;
    return;
  }
  // The entry load acts like a load from above (it is sent to the sides with `emit`), except that
  // in the patent rule set it enters with alpha1 (Rule::take).
  down_[s.eu + std::size_t(n0) * s.ev] = load.force;
  Box box{s.eu, s.eu, s.ev, s.ev};
  int layer = s.entry[a];
  for (int depth = 0;; layer += step, ++depth) {
    if (!pending_.empty()) clear_pending(slots, s.nd, layer, results);  // the previous solve's loads in this layer
    const auto here = slots.layer(a, layer);
    const bool last_layer = s.forward ? layer == g.cells[a] - 1 : layer == 0;
    double* const down_buf = down_.data();
    double* const next_down_buf = next_down_.data();
    Box next{INT_MAX, INT_MIN, INT_MAX, INT_MIN};
    Box ext = box;  // grows with friction chains and Poisson pushes
    if (s.alpha3 > 0) {
      s.friction_along_rows(here, box, down_buf, ext);
      if constexpr (Dim == 3) {
        s.template friction_along_lines<true>(here, box, down_buf, ext);
        s.template friction_along_lines<false>(here, box, down_buf, ext);
      }
    }
    s.take_loads(here, depth, last_layer, depth == 0, depth == 0 ? load.force : 0.0, ext, down_buf, next_down_buf, next);
    // Poisson: each squeezed agent pushes its side neighbours with (1 - beta) nu eps A E, which
    // they pass on along the push, decaying by poisson_decay per agent, until it falls to gamma.
    Box touched = ext;
    if (k_.beta < 1 && material_.poisson != 0) {
      const double push0 = (1 - k_.beta) * material_.poisson * g.face_area(s.l0) / g.face_area(a);
      s.push_along_rows(here, depth, push0, ext, touched);
      if constexpr (Dim == 3) {
        const double push1 = (1 - k_.beta) * material_.poisson * g.face_area(s.l1) / g.face_area(a);
        s.template push_along_lines<true>(here, depth, push1, ext, touched);
        s.template push_along_lines<false>(here, depth, push1, ext, touched);
      }
    }
    for (int v = ext.v_lo; v <= ext.v_hi; ++v) std::fill_n(s.top_buf + ext.u_lo + std::size_t(n0) * v, ext.u_hi - ext.u_lo + 1, 0.0);
    touched_.push_back({a, layer, touched});

    if (next.empty()) break;
    box = next;
    std::swap(down_, next_down_);
  }

  total += s.d;  // s.d's applied is 0 (the load is in total above); the sweep tallies no packets or returns
}

}  // namespace agent
