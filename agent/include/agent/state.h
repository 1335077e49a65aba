#pragma once
// The agent model's state under one load, from a LoadTransfer (its grid, material, coefficients
// and rule set) and the entry loads: agent::solve_state, the one call the study, Python and the
// calibration make. And the one table of the state's fields (agent::kStateFields), which the VTU
// and CSV writers, Python, the comparison's field list (compare::kFields) and so the summaries'
// metric names read (docs/compare.md, "The field table").
#include <agent/load_transfer.h>
#include <agent/transfer.h>
#include <workbench/symmetric_tensor.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>
#include <vector>

namespace agent {

/// Everything the agent model gives for one load state.
struct AgentState {
  std::vector<double> face_forces;                 ///< 2*dim per agent, grid order [N]
  std::vector<std::int32_t> generation;            ///< per agent, -1 where no load arrived
  std::vector<workbench::SymmetricTensor> stress;  ///< per agent [Pa] (2D plane stress: zz = yz = xz = 0)
  /// Per agent: the normal strains xx, yy, zz (Hooke's law of the normal stresses, agent_strains);
  /// the shear strains are not kept (0): node_displacements_marched takes gamma from the shear stress.
  std::vector<workbench::SymmetricTensor> strain;
  std::vector<double> displacement;  ///< dim per node [m], Grid::node_index order
  Diagnostics diagnostics;
};

/// The state of `model` under `loads` (each at its full force: a push marches inward with a force
/// >= 0, a pull with the same direction and a negative force) scaled by `factor` (a load step).
/// The relative threshold is a share of the full load (the sum of |force|), the same at every
/// step. Pulls are carried as the same pushes and the state negated: with pushes and pulls mixed,
/// the pushes' state less the pulls' (docs/agent-model.md, "Tension"). `stress_readings` apply to
/// every rule set but the columns (which give their stresses themselves); with them every load
/// moves in one direction. Throws CyclicCapReached at the cyclic transfer's cap.
AgentState solve_state(LoadTransfer& model, const std::vector<EntryLoad>& loads, const StressReadings& stress_readings,
                       double factor);

/// Adds `part`'s state to `total` (empty: becomes `part`): loads carried by different rule sets
/// superpose, as linear elasticity's do. Generations the earlier, the balances added.
void superpose(AgentState& total, const AgentState& part);

/// Where a field lives.
enum class FieldPlace { Agent, Node };
/// How a field is written to a VTU file: one array per component named by the component
/// (Scalars), one array of named components (Vector), or one array of three components, zero
/// beyond the mesh's dimension (Vector3: a vector in space, which ParaView warps by).
enum class VtuLayout { Scalars, Vector, Vector3 };

/// A row of the field table.
struct StateField {
  const char* name;  ///< the Python key and, for a Vector field, the VTU array's name
  const char* unit;  ///< written "[unit]" after each VTU array's and CSV column's name
  FieldPlace place;
  VtuLayout vtu;
  std::array<int, 2> count;    ///< components in 2D, in 3D
  const char* const* columns;  ///< per component: its CSV column, Scalars VTU array and compared name;
                               ///< a Vector's VTU component label is the part after the first '_'
  int slot;                    ///< the compare::StressSlot of component 0 (+1 per component); -1 none
  bool integer;                ///< whole numbers: Python int32, the CSV column without a unit
  /// Component `component` of agent or node `at` in a `dim`-D state.
  double (*read)(const AgentState& state, std::size_t at, int component, int dim);
  constexpr int components(int dim) const { return count[dim == 3 ? 1 : 0]; }
};

namespace field_columns {
inline constexpr const char* kGeneration[] = {"generation"};
inline constexpr const char* kFaceForce[] = {"f_-x", "f_+x", "f_-y", "f_+y", "f_-z", "f_+z"};  // f_ kDirectionNames
inline constexpr const char* kNormal[] = {"sigma_x", "sigma_y", "sigma_z"};
inline constexpr const char* kShear[] = {"tau_xy", "tau_yz", "tau_xz"};  // Voigt order from kXY
inline constexpr const char* kVonMises[] = {"von_mises"};
inline constexpr const char* kStrain[] = {"eps_x", "eps_y", "eps_z"};
inline constexpr const char* kDisplacement[] = {"u_x", "u_y", "u_z"};
}  // namespace field_columns

/// The von Mises stress of an agent: 2D agents in the plane-stress order they have always had.
inline double agent_von_mises(const workbench::SymmetricTensor& s, int dim) {
  return workbench::von_mises(s, dim == 3 ? workbench::VonMisesForm::General : workbench::VonMisesForm::PlaneStress);
}

/// Every field of AgentState, in the order of the VTU arrays and the CSV columns. A new field is a
/// row here and the function that reads it (docs/compare.md, "The field table").
inline constexpr StateField kStateFields[] = {
    {"generation", "-", FieldPlace::Agent, VtuLayout::Scalars, {1, 1}, field_columns::kGeneration, -1, true,
     [](const AgentState& s, std::size_t c, int, int) { return double(s.generation[c]); }},
    {"face_force", "N", FieldPlace::Agent, VtuLayout::Vector, {4, 6}, field_columns::kFaceForce, -1, false,
     [](const AgentState& s, std::size_t c, int k, int dim) { return s.face_forces[c * std::size_t(2 * dim) + k]; }},
    {"stress", "Pa", FieldPlace::Agent, VtuLayout::Scalars, {2, 3}, field_columns::kNormal, workbench::kXX, false,
     [](const AgentState& s, std::size_t c, int k, int) { return s.stress[c][workbench::kXX + k]; }},
    {"shear", "Pa", FieldPlace::Agent, VtuLayout::Scalars, {1, 3}, field_columns::kShear, workbench::kXY, false,
     [](const AgentState& s, std::size_t c, int k, int) { return s.stress[c][workbench::kXY + k]; }},
    {"von_mises", "Pa", FieldPlace::Agent, VtuLayout::Scalars, {1, 1}, field_columns::kVonMises, workbench::kVoigtCount,
     false, [](const AgentState& s, std::size_t c, int, int dim) { return agent_von_mises(s.stress[c], dim); }},
    {"strain", "-", FieldPlace::Agent, VtuLayout::Vector, {3, 3}, field_columns::kStrain, -1, false,
     [](const AgentState& s, std::size_t c, int k, int) { return s.strain[c][workbench::kXX + k]; }},
    {"displacement", "m", FieldPlace::Node, VtuLayout::Vector3, {2, 3}, field_columns::kDisplacement, -1, false,
     [](const AgentState& s, std::size_t n, int k, int dim) { return s.displacement[n * std::size_t(dim) + k]; }},
};

/// The row named `name` (a compile-time lookup where used as a constant).
constexpr const StateField& state_field(std::string_view name) {
  for (const auto& f : kStateFields)
    if (name == f.name) return f;
  throw "no such field in agent::kStateFields";
}

/// A Vector field's VTU label of component `column`: its name after the first '_' ("f_-x": "-x").
constexpr std::string_view vtu_label(std::string_view column) { return column.substr(column.find('_') + 1); }

}  // namespace agent
