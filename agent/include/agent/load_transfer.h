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
// LoadTransfer is a facade: it validates the grid, the material and the loads, and runs one of
// four rule types, chosen at construction from the rule set and the transfer readings:
//   agent::LayerSweep           patent (readings 2 and 6 off) and conserving: the layer sweep (agent/sweep.h);
//   agent::DirectionalTransfer  the directional rule set: the packet fan (agent/directional.h);
//   agent::CyclicTransfer       patent under readings 2 and/or 6: the work-list (agent/cyclic_transfer.h);
//   agent::ColumnTransfer       the columns rule set: beam sections (agent/columns.h), 2D and 3D.
// Each rule type checks its own coefficients and owns what it produces: the results it sizes
// (size_results) and fills (solve), its stress components (stress_components) and how far it
// reaches across a march (lateral_reach). The stress readings (4, 5) are not the transfer's:
// agent_stresses (agent/fields.h) takes them.
#include <agent/coefficients.h>
#include <agent/columns.h>
#include <agent/cyclic_transfer.h>
#include <agent/directional.h>
#include <agent/grid.h>
#include <agent/sweep.h>
#include <agent/transfer.h>

#include <cstdint>
#include <variant>
#include <vector>

namespace agent {

/// Every rule type, one of which a LoadTransfer runs.
using RuleType = std::variant<LayerSweep, DirectionalTransfer, CyclicTransfer, ColumnTransfer>;

/// A rule type as a value: RuleTag<T>::type is T.
template <class T>
struct RuleTag {
  using type = T;
};

/// Calls f(RuleTag<T>{}) with the rule type T of the rule set and the transfer readings, and
/// returns what f returns: the one place that maps a rule set to its type.
template <class F>
decltype(auto) with_rule_type(RuleSet rules, const TransferReadings& readings, F&& f) {
  if (rules == RuleSet::Directional) return f(RuleTag<DirectionalTransfer>{});
  if (rules == RuleSet::Columns) return f(RuleTag<ColumnTransfer>{});
  if (readings.cyclic()) return f(RuleTag<CyclicTransfer>{});
  return f(RuleTag<LayerSweep>{});
}

/// Agents per row the rule set reaches sideways from the agents a march reaches (its rule type's
/// lateral_reach): the directional fan ceil(tan(fan_angle)); the others the box's widest side.
/// RuleSet::Auto has none of its own (std::invalid_argument): ask the rule set it chose.
int lateral_reach(const Grid& grid, RuleSet rules, const Coefficients& k, const TransferReadings& readings = {});

/// Which stress components the rule set's rule type models under `loads`, and whether its fields
/// include a closed-form layer (its rule type's stress_model; agent/stress_components.h). Auto:
/// std::invalid_argument (agent_study::stress_model unites the rule sets it chose).
StressModel stress_model(const Grid& grid, RuleSet rules, const Coefficients& k, const TransferReadings& readings,
                         const std::vector<EntryLoad>& loads);

class LoadTransfer {
 public:
  /// Throws std::invalid_argument for a grid that is not set up, a material or coefficients
  /// outside their ranges (docs/agent-model.md), RuleSet::Auto (a study's choice per load, which
  /// checks its coefficients first), a transfer reading with a rule set it does not
  /// belong to (each is a reading of the patent rule set), and under readings 2 and 6 gamma = 0 or
  /// a transfer factor >= 1 (agent::check_cyclic: the cyclic transfer would not end). A Readings
  /// converts: its stress readings are not the transfer's (agent_stresses takes them).
  LoadTransfer(const Grid& grid, Material material, Coefficients coefficients, RuleSet rules,
               TransferReadings readings = {});

  /// Propagates the loads from a clean state. Loads superpose: each entry load is swept on its own.
  /// The sweep clears only what its previous solve touched (cost follows reach); the directional
  /// and cyclic rule types clear every slot first. Under readings 2 or 6 throws
  /// agent::CyclicCapReached if the work-list's cap is reached.
  void solve(const std::vector<EntryLoad>& loads);
  /// The same with the relative threshold taken as a share of `entering` [N] (the load entering
  /// the body) rather than of these loads' sum: a study that solves its pushes and its pulls apart
  /// gives both the threshold of the whole load. Under the absolute threshold `entering` is not read.
  void solve(const std::vector<EntryLoad>& loads, double entering);
  /// The absolute threshold the last solve dropped loads by [N] (Coefficients::gamma_for).
  double gamma_in_effect() const { return gamma_; }

  const Grid& grid() const { return grid_; }
  const Material& material() const { return material_; }
  const Coefficients& coefficients() const { return k_; }
  RuleSet rules() const { return rules_; }
  const TransferReadings& readings() const { return readings_; }
  /// Compressive normal force on each face of each agent [N], 2*dim per agent, by direction.
  const std::vector<double>& face_forces() const { return out_.faces; }
  /// Transfers from the entry agent to each agent; -1 where no load arrived.
  const std::vector<std::int32_t>& generation() const { return out_.generation; }
  const Diagnostics& diagnostics() const { return out_.diagnostics; }
  /// TransferResults::shear (the directional and column rule sets': the shear stress per slot [Pa];
  /// empty for the others) and ::balance (the directional rule set's row moment balance's slopes
  /// per march axis and layer).
  const std::vector<double>& shear_stress() const { return out_.shear; }
  const std::vector<double>& balance_slopes() const { return out_.balance; }
  /// The last solve's stress components, as its rule type gives them (`normal`: agent_stresses',
  /// `loads`: the solve's; agent/stress_components.h).
  StressComponents stress_components(const std::vector<double>& normal, const std::vector<EntryLoad>& loads) const;
  /// TransferResults::displacement: the column rule set's node displacements (empty for the others).
  const std::vector<double>& displacement() const { return out_.displacement; }
  /// Bytes held for the grid's slots (results, the grid's flags and tile table, the rule type's
  /// scratch between solves).
  std::size_t memory_bytes() const;

 private:
  Grid grid_;
  Material material_;
  Coefficients k_;
  RuleSet rules_;
  TransferReadings readings_;
  TransferResults out_;
  double gamma_;  // the gamma the rule type was built with
  RuleType transfer_;
};

}  // namespace agent
