// LoadTransfer: validation, and the rule type chosen from the rule set and the transfer readings.
#include <agent/load_transfer.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <type_traits>

namespace agent {

namespace {
void check(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

constexpr const char* kAutoIsAStudyChoice =
    "the auto rule set chooses a rule set per load (agent_study::transfer_model): a LoadTransfer runs one";

Coefficients with_gamma(Coefficients k, double gamma);

// The rule type of (rule set, readings) at the absolute threshold `gamma`, each checking its own coefficients.
RuleType make_transfer(const Grid& grid, const Material& material, const Coefficients& case_k, double gamma,
                       RuleSet rules, const TransferReadings& readings) {
  check_coefficients(case_k, rules);  // as the case gave them: a bad gamma_relative is named as such
  check(rules != RuleSet::Auto, kAutoIsAStudyChoice);
  const Coefficients k = with_gamma(case_k, gamma);
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
  return with_rule_type(rules, readings, [&](auto type) -> RuleType {
    using T = typename decltype(type)::type;
    if constexpr (std::is_same_v<T, DirectionalTransfer>) return T(k);
    else if constexpr (std::is_same_v<T, ColumnTransfer>) return T(grid, material);
    else if constexpr (std::is_same_v<T, CyclicTransfer>) return T(grid, material, k, readings);
    else return T(grid, material, k, rules, readings);
  });
}
// The rule types read the absolute threshold: `k` with gamma set to the one in effect.
Coefficients with_gamma(Coefficients k, double gamma) {
  k.gamma = gamma;
  return k;
}
}  // namespace

void TransferResults::clear_all() {
  std::fill(faces.begin(), faces.end(), 0.0);
  std::fill(generation.begin(), generation.end(), -1);
  std::fill(shear.begin(), shear.end(), 0.0);
  std::fill(balance.begin(), balance.end(), 0.0);
  std::fill(displacement.begin(), displacement.end(), 0.0);
  diagnostics = Diagnostics{};
}

void TransferResults::size_forces(const Grid& grid) {
  faces.assign(grid.count() * 2 * grid.dim, 0.0);
  generation.assign(grid.count(), -1);
}

int lateral_reach(const Grid& grid, RuleSet rules, const Coefficients& k, const TransferReadings& readings) {
  check(rules != RuleSet::Auto, kAutoIsAStudyChoice);
  return with_rule_type(rules, readings, [&](auto type) { return decltype(type)::type::lateral_reach(grid, k); });
}

StressModel stress_model(const Grid& grid, RuleSet rules, const Coefficients& k, const TransferReadings& readings,
                         const std::vector<EntryLoad>& loads) {
  check(rules != RuleSet::Auto, kAutoIsAStudyChoice);
  return with_rule_type(rules, readings, [&](auto type) { return decltype(type)::type::stress_model(grid, k, loads); });
}

LoadTransfer::LoadTransfer(const Grid& grid, Material material, Coefficients k, RuleSet rules,
                           TransferReadings readings)
    : grid_(grid), material_(material), k_(k), rules_(rules), readings_(readings), gamma_(k.gamma_for(1.0)),
      transfer_(make_transfer(grid, material, k, gamma_, rules, readings)) {
  std::visit([&](const auto& t) { t.size_results(grid, out_); }, transfer_);
}

StressComponents LoadTransfer::stress_components(const std::vector<double>& normal,
                                                 const std::vector<EntryLoad>& loads) const {
  return std::visit([&](const auto& t) { return t.stress_components(grid_, out_, normal, material_.poisson, loads); },
                    transfer_);
}

std::size_t LoadTransfer::memory_bytes() const {
  const std::size_t doubles =
      out_.faces.capacity() + out_.shear.capacity() + out_.balance.capacity() + out_.displacement.capacity();
  return doubles * sizeof(double) + out_.generation.capacity() * sizeof(std::int32_t) + grid_.flags.capacity() +
         grid_.tiles.memory_bytes() + std::visit([](const auto& t) { return t.memory_bytes(); }, transfer_);
}

void LoadTransfer::solve(const std::vector<EntryLoad>& loads) {
  double entering = 0;
  for (const auto& load : loads) entering += load.force;
  solve(loads, entering);
}

void LoadTransfer::solve(const std::vector<EntryLoad>& loads, double entering) {
  for (const auto& load : loads) {
    check(load.cell < grid_.count() && !grid_.is_air(load.cell),
          "entry load outside the body (cell " + std::to_string(load.cell) + ")");
    check(load.dir >= 0 && load.dir < 2 * grid_.dim, "entry load direction out of range");
    check(load.force >= 0 && std::isfinite(load.force), "entry load force must be finite and >= 0");
  }
  // A relative threshold scales with the load entering: the rule type is rebuilt when it changes
  // (each load step), and then knows nothing of what its last solve wrote.
  if (const double g = k_.gamma_for(entering); entering > 0 && g != gamma_) {
    transfer_ = make_transfer(grid_, material_, k_, g, rules_, readings_);
    gamma_ = g;
    out_.clear_all();
  }
  std::visit([&](auto& t) { t.solve(grid_, loads, out_); }, transfer_);
}

}  // namespace agent
