#pragma once
// Fields of both models on the agent grid, in the same layout, so that any two can be compared:
// every stress component and von Mises per agent (grid order) and the displacement per grid node;
// and the list of the fields a comparison compares (kFields), rows of the agents' field table
// (agent::kStateFields). FEM results are sampled onto the agents by point location (no case
// files, no I/O).
#include <agent/mesh_import.h>
#include <agent/state.h>
#include <fem_reference/fem_result.h>
#include <workbench/symmetric_tensor.h>

#include <array>
#include <iterator>
#include <string>
#include <string_view>
#include <vector>

namespace compare {

/// The stress slots of an agent in GridFields::stress: the six components (a
/// workbench::SymmetricTensor's, agent::StateField::slot's) and von Mises.
enum StressSlot : int {
  kSigmaX = workbench::kXX, kSigmaY = workbench::kYY, kSigmaZ = workbench::kZZ,
  kTauXY = workbench::kXY, kTauYZ = workbench::kYZ, kTauXZ = workbench::kXZ,
  kVonMises = workbench::kVoigtCount, kStressSlots
};

struct GridFields {
  std::vector<double> stress;  ///< kStressSlots per agent [Pa], grid order (2D: zz, yz, xz as the model gives them)
  std::vector<double> u;       ///< dim per grid node [m], Grid::node_index order
};

/// The von Mises stress of the six components xx, yy, zz, xy, yz, xz (the general form, for both
/// models' fields on the grid: workbench/symmetric_tensor.h).
using workbench::von_mises;

/// A field a comparison compares: a stress slot per agent, or one displacement component per node
/// (`component` -1: every component, the displacement as a vector).
struct FieldSpec {
  const char* name;
  bool per_node;
  int slot;           ///< StressSlot (per agent) or displacement component (per node, -1 all)
  int dims;           ///< bit 2: compared in 2D, bit 3: in 3D
  bool ratios;        ///< also the median ratio and the masked share (the seed's normal stresses)
  const char* unit;
  bool in(int dim) const { return dims & (1 << dim); }
};

/// Component `component` of the agents' field `name` (agent::kStateFields) as a compared field:
/// its column's name and unit, compared in the dimensions that have it; a stress's slot, a node
/// field's component. `component` -1: a node field whole, by the field's name (the displacement
/// as a vector).
constexpr FieldSpec compared(std::string_view name, int component, bool ratios = false) {
  const agent::StateField& f = agent::state_field(name);
  const bool per_node = f.place == agent::FieldPlace::Node;
  const int whole = component < 0 ? 0 : component;
  const int dims = (f.components(2) > whole ? 0b100 : 0) | (f.components(3) > whole ? 0b1000 : 0);
  return {component < 0 ? f.name : f.columns[component], per_node, per_node ? component : f.slot + component,
          dims, ratios, f.unit};
}

/// Every field compared, in the order of the summary: the seed's Figures 8-11 fields first
/// (sigma_x, sigma_y, displacement), then the others. The names, per scope, are the metric names'
/// middle part ("far.tau_xy.rel_l2").
inline constexpr FieldSpec kFields[] = {
    compared("stress", 0, true), compared("stress", 1, true), compared("displacement", -1),
    compared("stress", 2),       compared("shear", 0),        compared("shear", 1),
    compared("shear", 2),        compared("von_mises", 0),    compared("displacement", 0),
    compared("displacement", 1), compared("displacement", 2),
};

/// The place of the field `name` in kFields (a compile-time lookup: an unknown name does not compile
/// where it is used as a constant).
constexpr std::size_t field_index(std::string_view name) {
  for (std::size_t i = 0; i < std::size(kFields); ++i)
    if (name == kFields[i].name) return i;
  throw "no such field in compare::kFields";
}

/// The relative L2 error of predicting zero everywhere (the zero model), beside which every
/// relative L2 error is read: a model whose error is not below it is worse than predicting nothing.
constexpr double kZeroModelRelL2 = 1.0;
/// A relative error whose reference's own error (its distance from the estimate level, the same
/// norm) is at least this is not judged against the zero model: the reference does not resolve the
/// field there (e.g. tau_xy or u_x along a line of symmetry, where FEM's values are round-off).
constexpr double kUnresolvedReferenceError = 0.5;

/// The FEM result on the agent grid, found by point location (not by element order): an agent's
/// stress is the mean of the FEM cells whose centre lies in it, a grid node's displacement is
/// the FEM node at the same point. Works for any FEM mesh of the same body whose cells are no
/// larger than the agents and whose nodes include the agent nodes (the agents' own mesh, refined
/// or not). Throws workbench::Error naming `case_name` when an agent of the body gets no FEM cell
/// or a node of the body no FEM node.
GridFields fem_on_grid(const agent::ImportedMesh& mesh, const fem_reference::FemResult& fem,
                       const std::string& case_name);

/// The fields of an agent model on `source`, another grid of the same body (another agent size), on
/// `grid`: an agent's stress is the mean over its 2 x 2 (2 x 2 x 2) Gauss points of the source agent
/// holding each, von Mises of that mean, or, when one source agent holds them all (a coarser grid),
/// that agent's stress record whole; a node's displacement is the source's there (sample_nodes:
/// bilinear, exact where the grids share nodes). A Gauss point in the source's air takes
/// sample_cells's value there (its agent neighbours'). The same grid gives `fields` as they are.
/// Throws workbench::Error naming `what` when a point of `grid`'s body is in no source agent's reach.
GridFields agents_on_grid(const agent::Grid& grid, const agent::Grid& source, const GridFields& fields,
                          const std::string& what);

/// The points where a FEM on another mesh (the true geometry) is evaluated for the agents, as
/// FemProblem::probe_points: the 2 x 2 (2 x 2 x 2) Gauss points of every agent (grid order, air
/// left out), then every grid node of the body (Grid::node_index order).
std::vector<std::array<double, 3>> agent_probe_points(const agent::Grid& grid);

/// A FEM result solved with agent_probe_points(grid) as its probe points, on the agent grid: an
/// agent's stress is the mean of the FEM stress at its Gauss points inside the FEM mesh (the
/// agent's mean, as fem_on_grid gives on the agents' own mesh), a node's displacement the FEM
/// displacement at it. An agent wholly outside the FEM mesh (in the true body's hole or notch)
/// takes the stress of the FEM element whose centre is nearest, a node outside it the displacement
/// of the nearest FEM node; `outside` gets how many agents ([0]) and nodes ([1]) did.
GridFields fem_at_agents(const agent::Grid& grid, const fem_reference::FemResult& fem, std::array<std::size_t, 2>& outside);

}  // namespace compare
