#pragma once
// Stress, strain and displacement of the agents, from the face forces of a LoadTransfer.
#include <agent/grid.h>
#include <agent/load_transfer.h>

#include <array>
#include <vector>

namespace agent {

/// Normal stress per agent and axis [Pa], `dim` values per agent: the mean of the compressive
/// forces on the two opposite faces over the face area, negative in compression.
std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces);

/// Normal strains per agent, 3 values (eps_x, eps_y, eps_z), by Hooke's law: plane stress in 2D
/// (eps_z from the in-plane stresses), uniaxial-free 3D Hooke in 3D. Agents carry no shear.
std::vector<double> agent_strains(const Grid& grid, const Material& material, const std::vector<double>& stresses);

/// Where each displacement component is zero (docs/agent-model.md, "Displacement").
struct Datum {
  enum Kind { MinSide, MaxSide, Node } kind = MinSide;
  int node = 0;  ///< node index along the axis, for Kind::Node
};

/// The seed plate's choice, generalised: along an axis with a rigid outer side, integrate from
/// that side; otherwise from the node plane nearest the force-weighted centre of the entry loads.
std::array<Datum, 3> choose_datums(const Grid& grid, const std::vector<EntryLoad>& loads);

/// Nodal displacement [m], `dim` values per node (Grid::node_index order): each component is the
/// agent strain integrated along its axis from the datum, column by column, and averaged over
/// the columns that share the node.
std::vector<double> node_displacements(const Grid& grid, const std::vector<double>& strains,
                                       const std::array<Datum, 3>& datums);

}  // namespace agent
