// LoadTransfer: validation, and the rule type chosen from the rule set and the transfer readings.
#include <agent/load_transfer.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace agent {

namespace {
void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

// The rule type of (rule set, readings), each checking its own coefficients.
std::variant<LayerSweep, DirectionalTransfer, CyclicTransfer> make_transfer(const Grid& grid, const Material& material,
                                                                           const Coefficients& k, RuleSet rules,
                                                                           const TransferReadings& readings) {
  check(grid.dim == 2 || grid.dim == 3, "grid dimension must be 2 or 3");
  check(grid.flags.size() == grid.count(), "grid cells are not set up (use Grid::box)");
  check(material.young > 0 && std::isfinite(material.young), "young must be > 0");
  check(material.poisson > -1 && material.poisson < 0.5, "poisson must be in (-1, 0.5)");
  if (rules != RuleSet::Patent && (readings.cyclic() || readings.non_compounding_entry)) {
    check_coefficients(k, rules);
    check(!readings.cyclic(), "readings every_agent_all_operations and boundaries_return are readings of the "
                              "patent rule set");
    check(false, "reading non_compounding_entry is a reading of the patent rule set");
  }
  if (rules == RuleSet::Directional) return DirectionalTransfer(k);
  if (readings.cyclic()) return CyclicTransfer(grid, material, k, readings);
  return LayerSweep(grid, material, k, rules, readings);
}
}  // namespace

void TransferResults::clear_all() {
  std::fill(faces.begin(), faces.end(), 0.0);
  std::fill(generation.begin(), generation.end(), -1);
  std::fill(shear.begin(), shear.end(), 0.0);
  std::fill(balance.begin(), balance.end(), 0.0);
  diagnostics = Diagnostics{};
}

LoadTransfer::LoadTransfer(const Grid& grid, Material material, Coefficients k, RuleSet rules,
                           TransferReadings readings)
    : grid_(grid), material_(material), k_(k), rules_(rules), readings_(readings),
      transfer_(make_transfer(grid, material, k, rules, readings)) {
  out_.faces.assign(grid.count() * 2 * grid.dim, 0.0);
  out_.generation.assign(grid.count(), -1);
  if (rules == RuleSet::Directional) {  // the only rule type that writes them
    out_.shear.assign(grid.count() * (grid.dim == 3 ? 3 : 1), 0.0);
    out_.balance.assign(2 * balance_offset(grid, 3), 0.0);
  }
}

std::size_t LoadTransfer::memory_bytes() const {
  return (out_.faces.capacity() + out_.shear.capacity() + out_.balance.capacity()) * sizeof(double) + out_.generation.capacity() * sizeof(std::int32_t) +
         grid_.flags.capacity() + grid_.tiles.memory_bytes() +
         std::visit([](const auto& t) { return t.memory_bytes(); }, transfer_);
}

void LoadTransfer::solve(const std::vector<EntryLoad>& loads) {
  for (const auto& load : loads) {
    check(load.cell < grid_.count() && !grid_.is_air(load.cell),
          "entry load outside the body (cell " + std::to_string(load.cell) + ")");
    check(load.dir >= 0 && load.dir < 2 * grid_.dim, "entry load direction out of range");
    check(load.force >= 0 && std::isfinite(load.force), "entry load force must be finite and >= 0");
  }
  std::visit([&](auto& t) { t.solve(grid_, loads, out_); }, transfer_);
}

}  // namespace agent
