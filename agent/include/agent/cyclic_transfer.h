#pragma once
// Readings 2 and 6 of the patent rule set (docs/agent-model.md, "Readings"): every agent performs
// every transfer operation (friction to every side, back included; agents reached by friction or
// a push pass friction, the step along their load and pushes on), and boundary faces return the
// load into the body. The transfer graph then has cycles; this is the work-list iteration that
// solves it (the rule type agent::CyclicTransfer, which LoadTransfer chooses when either reading
// is on).
#include <agent/coefficients.h>
#include <agent/grid.h>
#include <agent/stress_components.h>
#include <agent/transfer.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

namespace agent {

/// The work-list stops with CyclicCapReached after this many agent updates, or when one wave would
/// hold more items (about 150 B each: 1.5 GB) (a second guard: CyclicTransfer's constructor already
/// refuses gamma = 0 and any transfer factor >= 1, so the iteration ends by itself;
/// docs/agent-model.md gives the proof and the bound). The seed plate needs 4 k (gamma 1e-3 N).
constexpr std::size_t kCyclicUpdateCap = 10'000'000;

/// The cap was reached: the results are incomplete. diagnostics().unfinished holds the load still
/// in transit; the face forces must not be used.
struct CyclicCapReached : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// The distinct factors whose products multiply a load under readings 2 and 6: alpha1 (entry and
/// friction loads on the TOP), alpha2 (along the load), alpha3 (friction), poisson_decay (along a
/// push) and the push factor (1 - beta) nu A_b / A_a for every pair of axes; a factor of 0 is left
/// out. The iteration ends when every factor but alpha1 is below 1 and gamma > 0 (alpha1 only
/// ever multiplies another factor; docs/agent-model.md gives the proof).
std::vector<double> cyclic_factors(const Grid& grid, const Material& material, const Coefficients& k);

/// Throws std::invalid_argument when the cyclic transfer would not end: gamma <= 0, or alpha2,
/// alpha3, poisson_decay or a push factor >= 1 (naming it).
void check_cyclic(const Grid& grid, const Material& material, const Coefficients& k);

/// Solves `loads` under readings 2 and/or 6 (`readings.every_agent_all_operations`,
/// `readings.boundaries_return`; reading 1, `non_compounding_entry`, is honoured too).
///
/// Inputs: the grid, the material, the patent rule set's coefficients (check_cyclic must pass) and
/// the entry loads. Outputs, added to (so the caller clears them first): `faces` (2*dim per agent:
/// the compressive normal force on each face [N], as LoadTransfer::face_forces), `generation` (per
/// agent the number of transfers from its entry at which a load first reached it; -1 unreached)
/// and `diagnostics` (applied = rigid_reaction + passed_out + dropped + lost to round-off, every
/// transfer but the Poisson pushes counted by its magnitude; pushes in the lateral_* terms;
/// boundary returns in returned_rigid / returned_free).
///
/// Each transfer at or below gamma is dropped on its own (the seed's threshold applies to every
/// transfer), so the result is the sum over every chain of transfers whose loads all exceed gamma.
/// Chains that reach the same agent in the same way (kind, direction, side) with the same product
/// of factors are merged before they are passed on: exact, and independent of the order of work.
/// Throws CyclicCapReached (diagnostics filled, `unfinished` > 0) after kCyclicUpdateCap updates.
void cyclic_transfer(const Grid& grid, const Material& material, const Coefficients& k, const TransferReadings& readings,
                     const std::vector<EntryLoad>& loads, std::vector<double>& faces,
                     std::vector<std::int32_t>& generation, Diagnostics& diagnostics,
                     std::size_t update_cap = kCyclicUpdateCap);

/// Readings 2 and/or 6 of the patent rule set as a LoadTransfer rule type.
class CyclicTransfer {
 public:
  /// Throws std::invalid_argument for coefficients outside their ranges (agent::check_coefficients)
  /// and when the iteration would not end (agent::check_cyclic).
  CyclicTransfer(const Grid& grid, const Material& material, const Coefficients& k, const TransferReadings& readings);
  /// Clears the whole result (loads move in every direction), then runs cyclic_transfer; throws
  /// CyclicCapReached at the cap.
  void solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out);
  /// Nothing is held between solves (the waves are allocated per solve).
  std::size_t memory_bytes() const { return 0; }

  /// The face forces and generations only.
  static void size_results(const Grid& grid, TransferResults& out) { out.size_forces(grid); }
  /// Friction and pushes go every way through the whole body: the box's widest side, in agents.
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

 private:
  Material material_;
  Coefficients k_;
  TransferReadings readings_;
};

}  // namespace agent
