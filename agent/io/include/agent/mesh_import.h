#pragma once
// Builds the agent grid from a gmsh mesh: a .geo file meshed through the gmsh API (with
// parameters passed as ONELAB numbers, e.g. the agent size h) or a ready .msh file.
// The mesh must be made of equal, axis-aligned squares (2D) or cubes (3D) on one lattice, in any
// arrangement (slots of the bounding box without an element are air); its physical groups of
// dimension dim-1 become named sets of boundary faces (loads, supports).
#include <agent/grid.h>

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace agent {

struct ImportedMesh {
  Grid grid;  ///< every outer face free; set supports with Grid::set_boundary
  /// Grid cell of each mesh element, in the mesh's element order (the order of VTU/CSV output).
  std::vector<std::size_t> cell_of_element;
  /// Outer faces of each named physical group of dimension dim-1.
  std::map<std::string, std::vector<BoundaryFace>> face_groups;
  /// Names of the geometry parameters the .geo file declares (DefineConstant).
  std::vector<std::string> parameters;
};

/// "(x, y)" or "(x, y, z)": a point or vector in messages and logs.
std::string point_text(const Eigen::Vector3d& x, int dim);

/// Bytes a study holds per slot of the grid's bounding box (agents and air), for the up-front
/// memory check.
double study_bytes_per_slot(int dim);

/// Bytes a study of these agents (box coordinates in a box of `cells`) holds, for the up-front
/// memory check: study_bytes_per_slot per slot id of the layout agent::lattice_layout picks,
/// plus on tiles the tile table (4 B an entry) and the sweep's three buffers of one box layer.
double study_bytes(int dim, const std::array<int, 3>& cells, const std::vector<std::array<int, 3>>& agents);

/// Reads or generates the mesh. `parameters` override the .geo's DefineConstant values; a name
/// the file does not declare is an error. Every error is a std::runtime_error whose message
/// starts with the file name and says what is wrong (element type, overlap, size, ...). `unit`:
/// metres per unit of the file's coordinates ([mesh] unit).
ImportedMesh import_mesh(const std::filesystem::path& file, const std::map<std::string, double>& parameters = {},
                         double unit = 1.0);

}  // namespace agent
