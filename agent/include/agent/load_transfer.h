#pragma once
// The agent load-transfer method of WO2001052193 (US7024344B1): a load entering the body is
// passed from agent to agent with transfer coefficients, and an agent exists only where the
// load reaching it exceeds the threshold gamma. The rules, rule by rule with the seed's
// passages and the choices made where the seed is open, are in docs/agent-model.md.
//
//   agent::LoadTransfer model(grid, {206e9, 0.3}, agent::Coefficients{}, agent::RuleSet::Patent);
//   model.solve({{entry_cell, agent::direction(1, false), 2.0}});   // 2 N downwards (-y)
//   const auto& f = model.face_forces();     // 2*dim compressive face forces per agent [N]
//
// Cost grows with the agents a load reaches, not with the body: solve() clears only what the
// previous solve touched.
#include <agent/coefficients.h>
#include <agent/cyclic_transfer.h>
#include <agent/directional.h>
#include <agent/grid.h>

#include <cstdint>
#include <optional>
#include <vector>

namespace agent {

/// Readings of the patent rule set where the seed's Japanese original supports more than one
/// (docs/agent-model.md, "Readings of the patent rules"). The defaults are the rules as first
/// implemented; a case names the readings it wants ([agent] readings, docs/case-file.md).
struct Readings {
  /// 1: alpha1 acts once, at entry: the entry agent passes P2 = alpha2 P0 on (not alpha2 alpha1 P0)
  /// and an agent reached by friction P3 passes alpha2 P3 on (not alpha2 alpha1 P3).
  bool non_compounding_entry = false;
  /// 4: an agent's stress along the load from the force on its entering face, not the mean of
  /// its two faces (agent_stresses).
  bool entering_face_stress = false;
  /// 5: an agent's stress across the load from its own lateral strain, eps_x = -beta nu eps_y
  /// (tension), not from the Poisson pushes on its faces (agent_stresses).
  bool lateral_strain_stress = false;
  /// 2: every agent performs every transfer operation: friction to every side (back included),
  /// and agents reached by friction or a push pass friction, the step along and pushes on. The
  /// transfer graph has cycles: solved by agent::cyclic_transfer (agent/cyclic_transfer.h).
  bool every_agent_all_operations = false;
  /// 6: a load reaching a boundary face is returned into the body (a free face reflects it, a
  /// rigid one returns its reaction), and the agent performs its operations on it
  /// (agent::cyclic_transfer). Supported with or without reading 2.
  bool boundaries_return = false;
  /// Readings 2 or 6: the transfer graph has cycles.
  bool cyclic() const { return every_agent_all_operations || boundaries_return; }
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

class LoadTransfer {
 public:
  /// Throws std::invalid_argument for coefficients outside their ranges (docs/agent-model.md).
  /// `readings` apply to the patent rule set only (the conserving one has its own normalised splits);
  /// readings 2 and 6 are refused with another rule set, and with gamma = 0 or a transfer factor
  /// >= 1 (agent::check_cyclic: the cyclic transfer would not end).
  LoadTransfer(const Grid& grid, Material material, Coefficients coefficients, RuleSet rules, Readings readings = {});

  /// Propagates the loads from a clean state. Loads superpose: each entry load is swept on its own.
  /// Under readings 2 or 6 throws agent::CyclicCapReached if the work-list's cap is reached.
  void solve(const std::vector<EntryLoad>& loads);

  const Grid& grid() const { return grid_; }
  const Material& material() const { return material_; }
  const Coefficients& coefficients() const { return k_; }
  const Readings& readings() const { return readings_; }
  /// Compressive normal force on each face of each agent [N], 2*dim per agent, by direction.
  const std::vector<double>& face_forces() const { return faces_; }
  /// Transfers from the entry agent to each agent; -1 where no load arrived.
  const std::vector<std::int32_t>& generation() const { return generation_; }
  const Diagnostics& diagnostics() const { return diagnostics_; }
  /// Bytes held for the grid's slots (results, the grid's flags, per-layer scratch).
  std::size_t memory_bytes() const;

 private:
  struct Box {
    int u_lo, u_hi, v_lo, v_hi;
    bool empty() const { return u_lo > u_hi; }
  };
  struct Touched {
    int axis, layer;
    Box box;
  };
  // Tiled: the grid is laid out on tiles (agent::Tiles): ids from box coordinates through the
  // tile table instead of strides.
  template <int Dim, bool Tiled>
  void sweep(const EntryLoad& load);
  void clear(const Touched& t);
  void clear_pending(int layer);
  void clear_all_pending();

  Grid grid_;
  Material material_;
  Coefficients k_;
  RuleSet rules_;
  Readings readings_;
  std::vector<double> faces_;
  std::vector<std::int32_t> generation_;
  Diagnostics diagnostics_;
  std::vector<Touched> touched_;  // what this solve's sweeps wrote, layer by layer
  std::vector<Touched> pending_;  // what the previous solve wrote, not yet cleared (sorted by layer)
  // Per-layer scratch, zero outside the active box: fresh (entry/friction) inputs, then each
  // agent's entering force; downward inputs; the downward inputs of the next layer. And one value
  // per line of a layer (a chain per column while a layer plane is scanned in row order).
  std::vector<double> fresh_, down_, next_down_, line_;
};

}  // namespace agent
