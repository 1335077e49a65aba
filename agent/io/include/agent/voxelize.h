#pragma once
// Voxelization: a gmsh geometry of any shape (a plate with a circular hole, a curved bracket, a 3D
// part) becomes an agent grid of equal squares or cubes of a given size. The rule, and how the
// physical groups are carried to the staircase, are in docs/agent-model.md ("Voxelization").
//
//   auto mesh = agent::voxelize("meshes/plate_hole.geo", 0.005, {}, "out/plate_hole_staircase.msh");
//   // FEM reads the written .msh: the identical staircase mesh, with the same group names.
#include <agent/mesh_import.h>

#include <filesystem>
#include <map>
#include <string>

namespace agent {

/// Meshes `geometry` (a .geo, with `parameters` as in import_mesh, or a .msh of any elements) and
/// lays a lattice of agents of edge `size` over the mesh's bounding box, starting at its lower
/// corner: an agent exists where its centre lies inside an element of the body. Every boundary
/// face of the staircase joins the physical groups (dimension dim-1) of the body-boundary element
/// nearest to the face's centre (none, when that element is in no group: a free face). When
/// `staircase_msh` is given, the staircase is written there as gmsh MSH (4-node quadrangles or
/// 8-node hexahedra in the physical group "body", the boundary groups as 2-node lines or 4-node
/// quadrangles), so that import_mesh and the FEM read the identical mesh. Errors are
/// std::runtime_error naming the file. `unit`: metres per unit of the geometry's coordinates
/// ([mesh] unit; `size` is in metres).
ImportedMesh voxelize(const std::filesystem::path& geometry, double size,
                      const std::map<std::string, double>& parameters = {},
                      const std::filesystem::path& staircase_msh = {}, double unit = 1.0);

/// Writes a voxelized mesh as voxelize's `staircase_msh` (coordinates in metres). Needs gmsh
/// initialised: a process that voxelized has it.
void write_staircase(const ImportedMesh& mesh, const std::filesystem::path& staircase_msh);

}  // namespace agent
