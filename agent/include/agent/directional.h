#pragma once
// The directional rule set: the project's extension of the agent method, not the seed's
// (docs/agent-model.md, "The directional rule set"). A load entering an agent is split into
// packets that each carry a slope from a fan; row by row every packet moves one agent along the
// load and drifts sideways by its slope, keeping its position inside the agent, so a load spreads
// linearly with depth (as in elasticity) while every agent still talks only to its neighbours.
#include <agent/coefficients.h>
#include <agent/grid.h>
#include <agent/stress_components.h>
#include <agent/transfer.h>

#include <cstdint>
#include <vector>

namespace agent {

/// The slopes of the fan along one lateral axis (lateral drift per unit depth) and the entry
/// weight of each (sum 1; in 3D a packet's weight is the product of its two axes' weights).
struct Fan {
  std::vector<double> slope, weight;
};
Fan entry_fan(const DirectionalCoefficients& k, int dim);

/// Adds the face forces, generations and diagnostics of `loads` (an entry load at or below gamma is
/// dropped; packets are not: a threshold per packet cuts the tails of the spreading fan, 62 % of
/// the load on the seed plate at 5 mm agents with gamma = 1e-3 N) to `faces` (2*dim per agent),
/// `generation` and `diagnostics`. Packets are moved, split and reflected whole, so nothing is
/// lost on the way (diagnostics.lost stays 0). Also the packets' shear per slot and the row moment
/// balance's slopes per march axis and layer (TransferResults::shear, ::balance; left alone when
/// empty). Paths::Turning: the turning paths, deposited row by row (docs/agent-model.md, "Turning
/// paths"); Paths::Mirror: straight rays mirrored by the free sides.
void directional_transfer(const Grid& grid, const DirectionalCoefficients& k, double gamma,
                          const std::vector<EntryLoad>& loads, std::vector<double>& faces,
                          std::vector<std::int32_t>& generation, Diagnostics& diagnostics, std::vector<double>& shear,
                          std::vector<double>& balance);

/// The directional rule set as a LoadTransfer rule type: it reads gamma and the directional
/// coefficients only, and takes no reading.
class DirectionalTransfer {
 public:
  /// Throws std::invalid_argument for coefficients outside their ranges (agent::check_coefficients).
  explicit DirectionalTransfer(const Coefficients& k);
  /// Clears the whole result (a row's moment balance reaches every agent of the row), then marches.
  void solve(const Grid& grid, const std::vector<EntryLoad>& loads, TransferResults& out);
  /// Nothing is held between solves (the rows are allocated per solve).
  std::size_t memory_bytes() const { return 0; }

  /// The face forces and generations, the packets' shear stress per slot and the row moment
  /// balance's slopes per march axis and layer (TransferResults::shear, ::balance).
  static void size_results(const Grid& grid, TransferResults& out) {
    out.size_forces(grid);
    out.shear.assign(grid.count() * std::size_t(shear_count(grid.dim)), 0.0);
    out.balance.assign(2 * balance_offset(grid, 3), 0.0);
  }
  /// A packet drifts at most the fan's widest slope per row: ceil(tan(fan_angle)) agents.
  static int lateral_reach(const Grid& grid, const Coefficients& k);
  /// The packets' shear, the row balance's and, with turning paths, the tie and the bonded face's
  /// layer (directional_stress_components).
  StressComponents stress_components(const Grid& grid, const TransferResults& out, const std::vector<double>& normal,
                                     double poisson, const std::vector<EntryLoad>& loads) const {
    return directional_stress_components(grid, normal, out.shear, out.balance, k_.directional, poisson, loads);
  }
  /// Every component; in 2D with turning paths and closed_forms "added" the fields include the
  /// closed-form layers (Kirsch's shear round a hole, the half-plane's layer on a bonded base).
  static StressModel stress_model(const Grid& grid, const Coefficients& k, const std::vector<EntryLoad>&) {
    const auto& d = k.directional;
    return {normal_stress_bits(grid.dim) | shear_bits(grid.dim),
            grid.dim == 2 && d.paths == Paths::Turning && d.closed_forms == ClosedForms::Added};
  }

 private:
  Coefficients k_;
};

}  // namespace agent
