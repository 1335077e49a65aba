#pragma once
// Stress, strain and displacement of the agents, from the face forces of a LoadTransfer.
#include <agent/grid.h>
#include <agent/transfer.h>

#include <array>
#include <vector>

namespace agent {

/// Normal stress per agent and axis [Pa], `dim` values per agent: the mean of the compressive
/// forces on the two opposite faces over the face area, negative in compression.
std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces);

/// The same under the stress readings (docs/agent-model.md, readings 4 and 5; any rule set's face
/// forces), for loads moving in direction `load_dir`: with entering_face_stress the stress along
/// the load is the force on the face the load enters by (opposite to load_dir) over its area; with
/// lateral_strain_stress each stress across the load is -beta nu times the stress along it (the
/// agent's own lateral strain eps_x = -beta nu eps_y as a stress, tension). Without either reading
/// it equals agent_stresses(grid, face_forces). A Readings converts (its transfer readings are
/// the transfer's).
std::vector<double> agent_stresses(const Grid& grid, const std::vector<double>& face_forces,
                                   const StressReadings& readings, int load_dir, double beta, double poisson);

/// Normal strains per agent, 3 values (eps_x, eps_y, eps_z), by Hooke's law: plane stress in 2D
/// (eps_z from the in-plane stresses), uniaxial-free 3D Hooke in 3D. The shear strain is not here:
/// node_displacements_marched takes gamma_xy from the shear stress.
std::vector<double> agent_strains(const Grid& grid, const Material& material, const std::vector<double>& stresses);

/// Where each displacement component is zero, per axis: a position along the axis in slots
/// from the grid's lower side (Grid::slot_coordinate: 0 = the lower outer side, cells[a] = the
/// upper one; agent lengths unless a run of air was collapsed). Strains integrate over agents
/// only (air carries none), so a collapsed air slot changes no displacement.
using Datums = std::array<double, 3>;

/// The seed plate's choice, generalised (docs/agent-model.md, "Displacement"): along an axis with
/// rigid faces across it, zero at the lowest one facing down the axis (else the highest facing
/// up); otherwise zero at the force-weighted centre of the loads.
Datums choose_datums(const Grid& grid, const std::vector<EntryLoad>& loads);

/// Nodal displacement [m], `dim` values per node (Grid::node_index order): each component is the
/// agent strain integrated along its axis from the datum, column by column, and averaged over
/// the columns that share the node.
std::vector<double> node_displacements(const Grid& grid, const std::vector<double>& strains,
                                       const Datums& datums);

/// With a shear (StressComponents::shear: tau_xy per slot in 2D; xy, yz, xz in 3D [Pa])
/// and loads marching along `march_axis` onto a rigid face: u along the march as
/// node_displacements gives it (zero at the rigid face), each u across it (u_l, l a lateral axis)
/// from eps_l along l and du_l/da = gamma_al - du_a/dl along the march: in 3D integrated along each
/// line of nodes along l, the line's constant the mean over the line of the marches from the rigid
/// face; in 2D the field closest to both in least squares, zero on the face (docs/agent-model.md,
/// "Displacement"). Other grids (tiled, air in the box, a datum along the march that is not a
/// whole side of the box): node_displacements as it is.
std::vector<double> node_displacements_marched(const Grid& grid, const std::vector<double>& strains,
                                               const std::vector<double>& shear, const Material& material,
                                               const Datums& datums, int march_axis);

/// Every node of a rigid face holds zero displacement: the face imposes it.
void hold_rigid_faces(const Grid& grid, std::vector<double>& u);

}  // namespace agent
