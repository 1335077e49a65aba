#pragma once
// The rule sets "patent" (without readings 2 and 6) and "conserving": every transfer goes one layer
// on in the load direction or straight on sideways, so the transfer graph has no cycles and a
// load is swept layer by layer (docs/agent-model.md, the rule sets and "Cost").
#include <agent/coefficients.h>
#include <agent/grid.h>
#include <agent/stress_components.h>
#include <agent/transfer.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace agent {

class LayerSweep {
 public:
  /// Throws std::invalid_argument for coefficients outside their ranges (agent::check_coefficients)
  /// and for reading 1 with the conserving rule set (it has its own normalised splits).
  LayerSweep(const Grid& grid, const Material& material, const Coefficients& k, RuleSet rules,
        const TransferReadings& readings);

  /// Clears what the previous solve wrote (and only that: cost follows reach, not the body), then
  /// sweeps each load on its own into `out`, whose arrays are sized for `grid`.
  void solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out);

  /// Bytes of the per-layer scratch and the lists of touched layers.
  std::size_t memory_bytes() const;

  /// The face forces and generations only.
  static void size_results(const Grid& grid, TransferResults& out) { out.size_forces(grid); }
  /// Friction passes a load along the whole row: the box's widest side, in agents.
  static int lateral_reach(const Grid& grid, const Coefficients&) { return std::max({grid.cells[0], grid.cells[1], grid.cells[2]}); }
  /// The normal stresses alone (normal_stress_components).
  static StressComponents stress_components(const Grid& grid, const TransferResults&, const std::vector<double>& normal,
                                            double, const std::vector<EntryLoad>&) {
    return normal_stress_components(grid, normal);
  }
  /// It models the normal stresses; its shears are not computed (0: not modelled).
  static StressModel stress_model(const Grid& grid, const Coefficients&, const std::vector<EntryLoad>&) {
    return {normal_stress_bits(grid.dim), false};
  }

  /// Lateral positions of a layer (u along l0, v along l1: agent::lateral_axes), inclusive.
  struct Box {
    int u_lo, u_hi, v_lo, v_hi;
    bool empty() const { return u_lo > u_hi; }
  };

 private:
  struct Touched {
    int axis, layer;
    Box box;
  };
  // How an agent takes its inputs and passes them on (a compile-time policy of the sweep).
  enum class RuleKind { Patent, PatentOnceAlpha1, Conserving };

  template <class Slots>
  void run(const Grid& grid, const Slots& slots, const EntryLoad& load, TransferResults& out);
  template <int Dim, class Slots, class Rule>
  void layers(const Grid& grid, const Slots& slots, const EntryLoad& load, TransferResults& out);
  template <class Slots>
  void clear(const Slots& slots, int nd, const Touched& t, TransferResults& out);
  template <class Slots>
  void clear_pending(const Slots& slots, int nd, int layer, TransferResults& out);
  template <class Slots>
  void clear_all_pending(const Slots& slots, int nd, TransferResults& out);

  Material material_;
  Coefficients k_;
  RuleKind rule_;
  std::vector<Touched> touched_;  // what this solve's sweeps wrote, layer by layer
  std::vector<Touched> pending_;  // what the previous solve wrote, not yet cleared (sorted by layer)
  // Per-layer scratch, zero outside the active box: fresh (entry/friction) inputs, then each
  // agent's entering force; downward inputs; the downward inputs of the next layer. And one value
  // per line of a layer (in 3D, a chain per line along l1 while a layer plane is scanned in row order).
  std::vector<double> fresh_, down_, next_down_, line_;
};

}  // namespace agent
