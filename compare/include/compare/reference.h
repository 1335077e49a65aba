#pragma once
// Fields of both models on the agent grid, in the same layout, so that any two can be compared:
// sigma_x, sigma_y per agent (grid order) and the displacement per grid node.
#include <agent_study.h>
#include <fem_reference/fem.h>

#include <vector>

namespace compare {

struct GridFields {
  std::vector<double> sigma;  ///< 2 per agent: sigma_x, sigma_y [Pa], grid order
  std::vector<double> u;      ///< dim per grid node [m], Grid::node_index order
};

/// The FEM result (gmsh element and node order) on the agent grid. Throws workbench::Error naming
/// `case_name` if the two meshes differ.
GridFields fem_on_grid(const agent_study::AgentStudy& study, const fem_reference::FemResult& fem,
                       const std::string& case_name);

/// An agent state in the same layout.
GridFields agent_on_grid(const agent_study::AgentStudy& study, const agent_study::AgentState& state);

}  // namespace compare
