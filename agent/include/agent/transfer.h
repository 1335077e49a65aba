#pragma once
// What every rule set of the agent method reads and writes: the material, the entry loads, the
// seed readings, and the results (face forces, generations, the load balance).
#include <agent/coefficients.h>
#include <agent/grid.h>

#include <cstddef>
#include <cstdint>
#include <vector>

namespace agent {

/// The readings of the patent rule set that change the transfer (docs/agent-model.md, "Readings
/// of the patent rules"): LoadTransfer chooses its rule type by them and refuses them with another
/// rule set.
struct TransferReadings {
  /// 1: alpha1 acts once, at entry: the entry agent passes P2 = alpha2 P0 on (not alpha2 alpha1 P0)
  /// and an agent reached by friction P3 passes alpha2 P3 on (not alpha2 alpha1 P3).
  bool non_compounding_entry = false;
  /// 2: every agent performs every transfer operation: friction to every side (back included),
  /// and agents reached by friction or a push pass friction, the step along and pushes on. The
  /// transfer graph has cycles: solved by agent::CyclicTransfer (agent/cyclic_transfer.h).
  bool every_agent_all_operations = false;
  /// 6: a load reaching a boundary face is returned into the body (a free face reflects it, a
  /// rigid one returns its reaction), and the agent performs its operations on it
  /// (agent::CyclicTransfer).
  /// Supported with or without reading 2.
  bool boundaries_return = false;
  /// Readings 2 or 6: the transfer graph has cycles.
  bool cyclic() const { return every_agent_all_operations || boundaries_return; }
};

/// The readings that change only how stresses are read from the face forces (agent_stresses,
/// agent/fields.h); they apply to every rule set and the transfer never sees them.
struct StressReadings {
  /// 4: an agent's stress along the load from the force on its entering face, not the mean of
  /// its two faces.
  bool entering_face_stress = false;
  /// 5: an agent's stress across the load from its own lateral strain, eps_x = -beta nu eps_y
  /// (tension), not from the Poisson pushes on its faces.
  bool lateral_strain_stress = false;
  bool any() const { return entering_face_stress || lateral_strain_stress; }
};

/// Every reading a case names ([agent] readings, docs/case-file.md); the defaults are the rules as
/// first implemented. LoadTransfer takes the transfer part, agent_stresses the stress part.
struct Readings : TransferReadings, StressReadings {
  bool operator==(const Readings& o) const {
    return non_compounding_entry == o.non_compounding_entry && entering_face_stress == o.entering_face_stress &&
           lateral_strain_stress == o.lateral_strain_stress &&
           every_agent_all_operations == o.every_agent_all_operations && boundaries_return == o.boundaries_return;
  }
};

struct Material {
  double young = 206e9;  ///< E [Pa]
  double poisson = 0.3;  ///< nu
};

/// A load entering the body: `force` [N] acting on agent `cell`, moving in direction `dir`
/// (see agent::direction); the agent receives it on its face opposite to `dir`.
struct EntryLoad {
  std::size_t cell;
  int dir;
  double force;
};

/// Where the load went. Forces in the load direction are kept apart from the sideways
/// (Poisson) pushes, which are self-equilibrated. In the load direction every newton is tallied
/// where it goes: applied = rigid_reaction + passed_out + dropped + lost (to round-off).
/// Under readings 2 and 6 (agent::cyclic_transfer) loads move in every direction: every transfer
/// but a push is tallied by its magnitude, and under reading 6 nothing leaves the body
/// (rigid_reaction = passed_out = 0): what the boundary faces returned is in returned_*.
struct Diagnostics {
  std::size_t agents_generated = 0;  ///< agents reached (generation >= 0)
  std::size_t agent_updates = 0;     ///< agent visits by the sweeps (the cost measure)
  std::size_t packet_moves = 0;      ///< packets moved by the directional rule set (its cost measure)
  double applied = 0;                ///< sum of the entry loads [N]
  double rigid_reaction = 0;         ///< load returned by rigid boundary agents [N]
  double passed_out = 0;             ///< load passed out through free faces [N]
  double dropped = 0;                ///< transfers at or below gamma, not passed on [N]
  /// Load lost through the transfer coefficients [N], summed agent by agent: what an agent
  /// receives less what it passes on (negative where the coefficients create load). Zero to
  /// round-off in the conserving rule set.
  double lost = 0;
  double lateral_reaction = 0;       ///< Poisson pushes returned by rigid faces [N]
  double lateral_passed_out = 0;     ///< Poisson pushes passed out through free faces [N]
  double lateral_dropped = 0;        ///< Poisson pushes at or below gamma [N]
  /// Reading 6: transfers (loads and pushes) that rigid faces returned into the body [N]: the
  /// load the rigid faces carried, not a term of the balance (it stays in the body).
  double returned_rigid = 0;
  double returned_free = 0;          ///< reading 6: transfers that free faces reflected [N]
  /// Load still in transit when the cyclic transfer's cap stopped it [N] (then solve() throws
  /// agent::CyclicCapReached): 0 in every complete result.
  double unfinished = 0;
};

/// Adds every tally of `o` to `d`: the one sum of two balances (a push's and a pull's state, a
/// layer's into its sweep's). agents_generated adds too: a caller that knows the union sets it.
inline Diagnostics& operator+=(Diagnostics& d, const Diagnostics& o) {
  d.agents_generated += o.agents_generated, d.agent_updates += o.agent_updates, d.packet_moves += o.packet_moves;
  d.applied += o.applied, d.rigid_reaction += o.rigid_reaction, d.passed_out += o.passed_out, d.dropped += o.dropped;
  d.lost += o.lost, d.lateral_reaction += o.lateral_reaction, d.lateral_passed_out += o.lateral_passed_out;
  d.lateral_dropped += o.lateral_dropped, d.returned_rigid += o.returned_rigid, d.returned_free += o.returned_free;
  d.unfinished += o.unfinished;
  return d;
}

/// The place of the shear between axes a != b in a 3D triple (xy, yz, xz); tau_xy is the 2D one.
constexpr int shear_pair(int a, int b) { return a + b == 1 ? 0 : a + b == 3 ? 1 : 2; }
/// Where the layers across axis a start in TransferResults::balance (2 values per layer).
inline std::size_t balance_offset(const Grid& g, int a) {
  std::size_t offset = 0;
  for (int b = 0; b < a; ++b) offset += std::size_t(g.cells[b]);
  return offset;
}

/// What a solve writes, indexed by slot id: 2*dim compressive face forces per slot [N] (by
/// direction), the generation (-1 where no load arrived) and the load balance.
struct TransferResults {
  std::vector<double> faces;
  std::vector<std::int32_t> generation;
  /// Per slot the shear stresses [Pa] a rule type writes, 1 in 2D (tau_xy), 3 in 3D (xy, yz, xz:
  /// shear_pair): the directional rule set's packets' (sum over the packets of force x lateral
  /// slope over the face area across their march, signed as the stress), the column rule set's
  /// sections' (tau = v Q / (I w)); empty for the others. The rule type's stress_components reads it.
  std::vector<double> shear;
  /// The directional rule set: per march axis a and layer across it (balance_offset), the two
  /// slopes (along l0, l1 of lateral_axes(a)) of the row moment balance's correction of the force
  /// along a: k0 (u - mean u) + k1 (v - mean v) [N] at an agent u, v agents from the box's lower
  /// sides (in `faces` too); its shear is read by vertical equilibrium.
  std::vector<double> balance;
  /// The column rule set (agent/columns.h): dim displacements per node id [m]; empty for the others,
  /// whose displacement is integrated from the stresses (agent/fields.h).
  std::vector<double> displacement;
  Diagnostics diagnostics;
  /// Zero forces, every generation -1, no diagnostics: what a rule type without its own
  /// bookkeeping of what it wrote does before a solve.
  void clear_all();
  /// Sizes `faces` and `generation` for `grid` (cleared): what every rule type writes. A rule type's
  /// size_results sizes these and the results of its own.
  void size_forces(const Grid& grid);
};

}  // namespace agent
