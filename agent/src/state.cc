// The agent model's state under one load: the transfer, then every field from it.
#include <agent/fields.h>
#include <agent/state.h>
#include <agent/stress_components.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace agent {

namespace {

static_assert(
    [] {
      for (int d = 0; d < 6; ++d)
        if (vtu_label(field_columns::kFaceForce[d]) != kDirectionNames[d]) return false;
      return true;
    }(),
    "the face force's columns are f_ and the direction names");

/// Per agent, the dim normal stresses and the shears (1 in 2D, 3 in 3D; none: zero) as one record.
std::vector<workbench::SymmetricTensor> records(const std::vector<double>& normal, const std::vector<double>& shear,
                                                std::size_t count, int dim) {
  const int shears = shear_count(dim);
  std::vector<workbench::SymmetricTensor> out(count, workbench::SymmetricTensor{});
  for (std::size_t c = 0; c < count; ++c) {
    for (int a = 0; a < dim; ++a) out[c][workbench::kXX + a] = normal[c * std::size_t(dim) + a];
    if (!shear.empty())
      for (int t = 0; t < shears; ++t) out[c][workbench::kXY + t] = shear[c * std::size_t(shears) + t];
  }
  return out;
}

/// The three normal strains per agent (agent_strains' layout) as records, shear strains 0.
std::vector<workbench::SymmetricTensor> strain_records(const std::vector<double>& strains) {
  std::vector<workbench::SymmetricTensor> out(strains.size() / 3, workbench::SymmetricTensor{});
  for (std::size_t c = 0; c < out.size(); ++c)
    for (int a = 0; a < 3; ++a) out[c][workbench::kXX + a] = strains[3 * c + a];
  return out;
}

/// The state of `pushes` (forces >= 0, marching inward) alone: the transfer and every field from
/// it. `entering` is the whole load's magnitude (the relative threshold's base), `datums` those of
/// the whole load, so that a pull's state is its push's to the bit. `load_dir`: the stress
/// readings' load direction.
AgentState carried(LoadTransfer& model, const std::vector<EntryLoad>& pushes, const StressReadings& readings,
                   int load_dir, double entering, const Datums& datums) {
  model.solve(pushes, entering);
  AgentState s;
  const auto& grid = model.grid();
  s.face_forces = model.face_forces();
  s.generation = model.generation();
  s.diagnostics = model.diagnostics();
  if (model.rules() == RuleSet::Columns) {  // the columns give the shear and the displacement themselves
    const auto normal = agent_stresses(grid, s.face_forces);
    const auto strain = agent_strains(grid, model.material(), normal);
    s.stress = records(normal, model.shear_stress(), grid.count(), grid.dim);
    s.strain = strain_records(strain);
    s.displacement = model.displacement();
    hold_rigid_faces(grid, s.displacement);
    return s;
  }
  const auto normal =
      agent_stresses(grid, s.face_forces, readings, load_dir, model.coefficients().beta, model.material().poisson);
  // Every component (agent/stress_components.h): the shear and, with turning paths, the tie.
  const auto parts = model.stress_components(normal, pushes);
  const auto strain = agent_strains(grid, model.material(), parts.sigma);
  s.displacement = model.shear_stress().empty()
                       ? node_displacements(grid, strain, datums)
                       : node_displacements_marched(grid, strain, parts.shear, model.material(), datums,
                                                    axis_of(pushes.front().dir));
  hold_rigid_faces(grid, s.displacement);
  s.stress = records(parts.sigma, parts.shear, grid.count(), grid.dim);
  s.strain = strain_records(strain);
  return s;
}

/// Every real number of a state that is written (face forces apart: see solve_state).
template <class Visit>
void for_each_field_value(AgentState& s, Visit visit) {
  for (auto* records : {&s.stress, &s.strain})
    for (auto& r : *records)
      for (double& v : r) visit(v);
  for (double& v : s.displacement) visit(v);
}

/// `a` + `sign` `b` in every field (-1: a push state less a pull's); generations the earlier,
/// balances added (the balance tallies magnitudes: a pull carried to a rigid face is a rigid reaction).
void combine(AgentState& a, const AgentState& b, double sign) {
  for (std::size_t i = 0; i < a.face_forces.size(); ++i) a.face_forces[i] += sign * b.face_forces[i];
  for (auto [x, y] : {std::pair{&a.stress, &b.stress}, std::pair{&a.strain, &b.strain}})
    for (std::size_t c = 0; c < x->size(); ++c)
      for (int k = 0; k < workbench::kVoigtCount; ++k) (*x)[c][k] += sign * (*y)[c][k];
  for (std::size_t i = 0; i < a.displacement.size(); ++i) a.displacement[i] += sign * b.displacement[i];
  for (std::size_t i = 0; i < a.generation.size(); ++i)
    a.generation[i] = std::int32_t(std::min(std::uint32_t(a.generation[i]), std::uint32_t(b.generation[i])));
  a.diagnostics += b.diagnostics;
  a.diagnostics.agents_generated =
      std::size_t(std::count_if(a.generation.begin(), a.generation.end(), [](auto g) { return g >= 0; }));
}

}  // namespace

AgentState solve_state(LoadTransfer& model, const std::vector<EntryLoad>& loads, const StressReadings& stress_readings,
                       double factor) {
  // Linear elasticity is odd in the load: the pulls are carried as the same pushes and subtracted
  // (docs/agent-model.md, "Tension"). Every rule set marches inward either way.
  std::vector<EntryLoad> pushes, pulls, all;
  double entering = 0;  // the whole load's magnitude
  for (auto l : loads) {
    entering += std::abs(l.force);
    l.force *= factor;
    (l.force < 0 ? pulls : pushes).push_back(l);
    if (l.force < 0) pulls.back().force = -l.force;
    all.push_back(l.force < 0 ? pulls.back() : l);
  }
  // The relative threshold is a share of the full load, the same at every load step: the steps
  // then grow the reached region as the seed's do, and the rule type is built once.
  const auto datums = choose_datums(model.grid(), all);
  const int load_dir = loads.empty() ? 0 : loads.front().dir;
  AgentState s = carried(model, pulls.empty() ? pushes : pulls, stress_readings, load_dir, entering, datums);
  if (pushes.empty()) {  // only pulls: the pushed state negated, to the bit (von Mises is even)
    for (double& v : s.face_forces) v = -v;
    for_each_field_value(s, [](double& v) { v = -v; });
  } else if (!pulls.empty()) {
    AgentState pushed = carried(model, pushes, stress_readings, load_dir, entering, datums);
    combine(pushed, s, -1.0);
    s = std::move(pushed);
  }
  // An unloaded agent's stress is -0 (a compression of nothing): written, it would read "-0".
  for_each_field_value(s, [](double& v) { v += 0.0; });
  return s;
}

void superpose(AgentState& total, const AgentState& part) {
  if (total.stress.empty()) {
    total = part;
    return;
  }
  combine(total, part, 1.0);
}

}  // namespace agent
