#pragma once
// A mesh as plain arrays, read from gmsh (or built as a box) before deal.II sees it.
#include <fem_reference/fem.h>

#include <array>
#include <cstddef>
#include <map>
#include <string>
#include <vector>

namespace fem_reference {

struct PlainMesh {
  std::string source;          ///< the mesh file (for messages)
  int dim = 2;
  bool simplex = false;        ///< triangles/tetrahedra instead of quadrilaterals/hexahedra
  int corners = 4;             ///< vertices per cell
  std::vector<double> nodes;   ///< 3 per node, gmsh node order (nodes of the cells only)
  /// corners per cell, node indices, in deal.II vertex order (lexicographic for quads/hexes).
  std::vector<unsigned> cells;
  /// Faces (dim-1) of each named physical group: node indices per face (2, 3 or 4 nodes).
  std::map<std::string, std::vector<std::vector<unsigned>>> face_groups;
  std::size_t cell_count() const { return cells.size() / corners; }
  std::size_t node_count() const { return nodes.size() / 3; }
};

/// Meshes a .geo (ONELAB parameters as in agent/src/mesh_import.cc) or reads a .msh through the gmsh API.
PlainMesh read_gmsh_mesh(const std::filesystem::path& file, const std::map<std::string, double>& parameters,
                         double unit = 1.0);

PlainMesh box_mesh(const Box& box);

/// The axis a group's faces are perpendicular to (all must lie in planes x_a = const); -1 if none.
int normal_axis(const PlainMesh& mesh, const std::string& group);

/// The largest side of the mesh's bounding box over the second largest (1 for a square or cube, 250
/// for a 500 x 2 mm strip).
double slenderness(const PlainMesh& mesh);

/// Solves on a plain mesh (problem/elastic_problem.cc).
FemResult solve_on_mesh(const FemProblem& problem, const PlainMesh& mesh, const std::filesystem::path& output_dir,
                        std::ostream* log, double mesh_seconds);

}  // namespace fem_reference
