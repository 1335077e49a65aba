#pragma once
// Fields of both models on the agent grid, in the same layout, so that any two can be compared:
// sigma_x, sigma_y per agent (grid order) and the displacement per grid node. FEM results are
// sampled onto the agents by point location (no case files, no I/O).
#include <agent/mesh_import.h>
#include <fem_reference/fem.h>

#include <array>
#include <string>
#include <vector>

namespace compare {

struct GridFields {
  std::vector<double> sigma;  ///< 2 per agent: sigma_x, sigma_y [Pa], grid order
  std::vector<double> u;      ///< dim per grid node [m], Grid::node_index order
};

/// The FEM result on the agent grid, found by point location (not by element order): an agent's
/// stress is the mean of the FEM cells whose centre lies in it, a grid node's displacement is
/// the FEM node at the same point. Works for any FEM mesh of the same body whose cells are no
/// larger than the agents and whose nodes include the agent nodes (the agents' own mesh, refined
/// or not). Throws workbench::Error naming `case_name` when an agent of the body gets no FEM cell
/// or a node of the body no FEM node.
GridFields fem_on_grid(const agent::ImportedMesh& mesh, const fem_reference::FemResult& fem,
                       const std::string& case_name);

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
