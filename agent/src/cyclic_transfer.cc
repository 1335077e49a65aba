// Readings 2 and 6 of the patent rule set: a work-list over the cyclic transfer graph, wave by wave.
#include <agent/cyclic_transfer.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <string>
#include <unordered_map>

namespace agent {

namespace {

enum Kind : std::uint8_t {
  kEntry,     // the load given to the body: TOP alpha1 P0
  kFriction,  // a friction load: enters the TOP with alpha1 (reading 1: whole)
  kAlong,     // from the agent behind, or returned by a boundary face: enters whole
  kPush,      // a Poisson push: enters whole, passed on with poisson_decay
};
constexpr std::uint8_t kAnySide = 7;  // a friction load under reading 2 goes on to every side
// Exponents of the distinct factors, 12 bits each, five to a word: a load is P0 times the
// product of the factors to these powers, and two chains with the same powers are merged.
constexpr int kBits = 12, kPerWord = 5, kMaxSlots = 2 * kPerWord;
constexpr int kMaxWaves = (1 << kBits) - 1;  // no exponent can exceed the number of transfers

struct Item {
  std::uint64_t e[2];
  std::size_t cell;
  std::uint8_t kind, dir, in_side;  // dir: where the load moves; in_side: the face it came by
  bool free_return;                 // came back through a free face: that face carries nothing
  double value;                     // the load of one chain [N] (what gamma is compared with)
  double weight;                    // the sum over the merged chains [N]
  bool same(const Item& o) const {
    return e[0] == o.e[0] && e[1] == o.e[1] && cell == o.cell && kind == o.kind && dir == o.dir &&
           in_side == o.in_side && free_return == o.free_return;
  }
};
struct ItemHash {
  std::size_t operator()(const Item& i) const {
    std::uint64_t h = i.e[0] * 0x9E3779B97F4A7C15ull ^ (i.e[1] + 0x632BE59BD9B4E019ull) * 0xC2B2AE3D27D4EB4Full;
    h ^= (std::uint64_t(i.cell) << 12 | std::uint64_t(i.kind) << 9 | std::uint64_t(i.dir) << 6 |
          std::uint64_t(i.in_side) << 3 | std::uint64_t(i.free_return)) * 0x165667B19E3779F9ull;
    return std::size_t(h ^ (h >> 29));
  }
};
struct ItemEqual {
  bool operator()(const Item& a, const Item& b) const { return a.same(b); }
};

// The distinct factor values and the slot of each use: alpha1, alpha2, alpha3, poisson_decay,
// and the push factor for a load along axis a pushing across axis b.
struct Factors {
  std::vector<double> values;
  int alpha1 = -1, alpha2 = -1, alpha3 = -1, decay = -1;
  int push[3][3] = {{-1, -1, -1}, {-1, -1, -1}, {-1, -1, -1}};
  double push_value[3][3] = {};
  int slot(double v) {
    if (v == 0) return -1;  // a zero factor passes nothing on
    for (std::size_t i = 0; i < values.size(); ++i)
      if (values[i] == v) return int(i);
    values.push_back(v);
    return int(values.size()) - 1;
  }
};

Factors factors_of(const Grid& g, const Material& m, const Coefficients& k) {
  Factors f;
  f.alpha1 = f.slot(k.alpha1);
  f.alpha2 = f.slot(k.alpha2);
  f.alpha3 = f.slot(k.alpha3);
  f.decay = f.slot(k.decay());
  for (int a = 0; a < g.dim; ++a)
    for (int b = 0; b < g.dim; ++b)
      if (a != b) {
        f.push_value[a][b] = (1 - k.beta) * m.poisson * g.face_area(b) / g.face_area(a);
        f.push[a][b] = f.slot(f.push_value[a][b]);
      }
  return f;
}

void bump(Item& i, int slot) {
  if (slot >= 0) i.e[slot / kPerWord] += std::uint64_t(1) << (kBits * (slot % kPerWord));
}

// The second guard: what is still in transit (`wave` from item `from` on, and `next`) is
// reported, and nothing computed so far may be used.
[[noreturn]] void stop_at_cap(Diagnostics& d, const std::vector<Item>& wave, std::size_t from,
                              const std::vector<Item>& next, int depth) {
  for (std::size_t i = from; i < wave.size(); ++i) d.unfinished += wave[i].weight;
  for (const auto& i : next) d.unfinished += i.weight;
  throw CyclicCapReached("cyclic transfer: stopped after " + std::to_string(d.agent_updates) + " agent updates and " +
                         std::to_string(depth) + " waves with " + std::to_string(d.unfinished) +
                         " N still in transit (the results are incomplete)");
}

}  // namespace

std::vector<double> cyclic_factors(const Grid& grid, const Material& material, const Coefficients& k) {
  return factors_of(grid, material, k).values;
}

void check_cyclic(const Grid& grid, const Material& material, const Coefficients& k) {
  auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (!(k.gamma > 0))
    fail("readings every_agent_all_operations / boundaries_return need gamma > 0 (the cyclic transfer ends when "
         "every transfer has fallen to gamma)");
  auto below_one = [&](double v, const std::string& name) {
    if (!(v < 1))
      fail("readings every_agent_all_operations / boundaries_return need every transfer factor below 1 (the cyclic "
           "transfer would not end): " + name + " = " + std::to_string(v));
  };
  // alpha1 <= 1 needs no check: it only ever multiplies another factor (alpha2 or a push factor).
  below_one(k.alpha2, "alpha2");
  below_one(k.alpha3, "alpha3");
  below_one(k.decay(), "poisson_decay");
  const Factors f = factors_of(grid, material, k);
  for (int a = 0; a < grid.dim; ++a)
    for (int b = 0; b < grid.dim; ++b)
      if (a != b)
        below_one(f.push_value[a][b], "the push factor (1 - beta) nu A_" + std::string(1, char('x' + b)) + " / A_" +
                                          std::string(1, char('x' + a)));
}

void cyclic_transfer(const Grid& g, const Material& material, const Coefficients& k, const TransferReadings& readings,
                     const std::vector<EntryLoad>& loads, std::vector<double>& faces,
                     std::vector<std::int32_t>& generation, Diagnostics& d, std::size_t update_cap) {
  check_cyclic(g, material, k);
  const Factors f = factors_of(g, material, k);
  if (f.values.size() > std::size_t(kMaxSlots)) throw std::logic_error("cyclic_transfer: too many distinct factors");
  const int nd = 2 * g.dim;
  const bool every_operation = readings.every_agent_all_operations;  // reading 2
  const bool returns = readings.boundaries_return;                   // reading 6
  const bool once_alpha1 = readings.non_compounding_entry;           // reading 1
  const bool pushes = k.beta < 1 && material.poisson != 0;
  const double gamma = k.gamma;

  std::vector<Item> wave, next;
  std::unordered_map<Item, std::size_t, ItemHash, ItemEqual> at;  // an item of `next` -> its place

  for (const auto& load : loads) {
    d.applied += load.force;
    if (!(load.force > gamma)) {
      d.dropped += load.force;
      continue;
    }
    wave.assign(1, Item{{0, 0}, load.cell, kEntry, std::uint8_t(load.dir), kAnySide, false, load.force, load.force});
    for (int depth = 0; !wave.empty(); ++depth) {
      next.clear();
      at.clear();
      if (depth > kMaxWaves || d.agent_updates + wave.size() > update_cap) stop_at_cap(d, wave, 0, next, depth);
      for (std::size_t n = 0; n < wave.size(); ++n) {
        if (next.size() > update_cap) stop_at_cap(d, wave, n, next, depth);  // the next wave alone would exceed the cap
        const Item& it = wave[n];
        ++d.agent_updates;
        const std::size_t c = it.cell;
        const auto current = std::uint32_t(generation[c]);
        d.agents_generated += current == UINT32_MAX;
        generation[c] = std::int32_t(std::min(current, std::uint32_t(depth)));
        double* fc = faces.data() + c * nd;
        const int m = it.dir, axis = axis_of(m);
        const bool top_alpha1 = it.kind == kEntry || (it.kind == kFriction && !once_alpha1);
        const double top = top_alpha1 ? k.alpha1 : 1.0;  // the TOP force per newton of input
        if (!it.free_return) fc[opposite(m)] += top * it.weight;
        const bool is_push = it.kind == kPush;
        double passed = 0;  // loads (not pushes) this agent passes on, for `lost`

        // One transfer of `factor` of the input (slots: its factors) leaving through face `side`.
        auto transfer = [&](double factor, int slot_a, int slot_b, Kind kind, int dir, int side, bool loads_face) {
          Item child = it;
          bump(child, slot_a);
          bump(child, slot_b);
          child.kind = kind;
          child.dir = std::uint8_t(dir);
          child.free_return = false;
          child.value = it.value * factor;
          child.weight = it.weight * factor;
          const bool push = kind == kPush;
          if (!push) passed += child.weight;
          if (!(child.value > gamma)) {
            (push ? d.lateral_dropped : d.dropped) += child.weight;
            return;
          }
          const std::size_t across = g.neighbour(c, side);
          if (across != Grid::npos && !g.is_air(across)) {
            if (loads_face) fc[side] += child.weight;
            child.cell = across;
            child.in_side = std::uint8_t(opposite(side));
          } else {
            const bool rigid = g.boundary(side, c) == Boundary::Rigid;
            if (!returns) {
              if (rigid && loads_face) fc[side] += child.weight;
              (rigid ? (push ? d.lateral_reaction : d.rigid_reaction) : (push ? d.lateral_passed_out : d.passed_out)) +=
                  child.weight;
              return;
            }
            // Reading 6: the boundary agent returns the load to this agent. A load along a chain or a
            // push comes back through the face it left by (a rigid face carries it on entry, a free
            // one nothing); a friction load comes back to this agent's TOP and goes on away from
            // that face.
            (rigid ? d.returned_rigid : d.returned_free) += child.weight;
            if (kind != kFriction) child.dir = std::uint8_t(opposite(dir));
            child.free_return = !rigid && kind != kFriction;
            child.in_side = std::uint8_t(side);
          }
          // Only a friction load's side steers it (straight on, without reading 2): merge the rest.
          if (kind != kFriction || every_operation) child.in_side = kAnySide;
          const auto [place, added] = at.emplace(child, next.size());
          if (added) next.push_back(child);
          else next[place->second].weight += child.weight;
        };

        // Along the load: alpha2 of the TOP (reading 1: of the input); a push goes on with poisson_decay.
        if (is_push) transfer(k.decay(), f.decay, -1, kPush, m, m, true);
        else if (top_alpha1 && !(it.kind == kEntry && once_alpha1))
          transfer(k.alpha1 * k.alpha2, f.alpha1, f.alpha2, kAlong, m, m, true);
        else transfer(k.alpha2, f.alpha2, -1, kAlong, m, m, true);
        // Friction, alpha3 of the input, onto the TOP of the agents beside: to every side (reading 2),
        // else from the entry and loads along to every side and a friction load straight on only.
        for (int s = 0; s < nd; ++s) {
          if (axis_of(s) == axis) continue;
          const bool goes = every_operation || it.kind == kEntry || it.kind == kAlong ||
                            (it.kind == kFriction && (it.in_side == kAnySide || s == opposite(it.in_side)));
          if (goes) transfer(k.alpha3, f.alpha3, -1, kFriction, m, s, false);
        }
        // Poisson: (1 - beta) nu A_side / A_top of the TOP force to every side; a pushed agent pushes
        // on only under reading 2.
        if (pushes && (!is_push || every_operation))
          for (int s = 0; s < nd; ++s) {
            if (axis_of(s) == axis) continue;
            const int b = axis_of(s);
            transfer(top * f.push_value[axis][b], top_alpha1 ? f.alpha1 : -1, f.push[axis][b], kPush, s, s, true);
          }
        // What this agent received (a push is not a load: it is tallied apart) less what it passed on.
        d.lost += (is_push ? 0.0 : it.weight) - passed;
      }
      wave.swap(next);
    }
  }
}

CyclicTransfer::CyclicTransfer(const Grid& grid, const Material& material, const Coefficients& k,
                               const TransferReadings& readings)
    : material_(material), k_(k), readings_(readings) {
  check_coefficients(k, RuleSet::Patent);
  check_cyclic(grid, material, k);
}

void CyclicTransfer::solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out) {
  out.clear_all();
  cyclic_transfer(grid, material_, k_, readings_, loads, out.faces, out.generation, out.diagnostics);
}

}  // namespace agent
