#pragma once
// A line or surface mesh as the PBD model reads it: points, cells (2-node lines, 3-node triangles,
// 4-node quadrilaterals, VTK numbering) and named node groups. Filled by pbd_io (gmsh, OBJ, VTU)
// or by the embedding program.
#include <pbd/particles.h>

#include <map>
#include <string>
#include <vector>

namespace pbd {

enum CellType : int { kLine = 3, kTriangle = 5, kQuad = 9 };  ///< VTK cell type numbers
int corner_count(int cell_type);  ///< 2, 3, 4; 0 for an unknown type

struct Mesh {
  std::vector<Vec3> points;
  std::vector<int> cell_types;
  std::vector<int> cell_nodes;    ///< corners, cell after cell
  std::vector<int> cell_offsets{0};  ///< cell c has nodes [cell_offsets[c], cell_offsets[c+1])
  std::map<std::string, std::vector<int>> groups;  ///< named node sets (gmsh physical groups, ...)

  std::size_t cell_count() const { return cell_types.size(); }
  void add_cell(int type, std::initializer_list<int> nodes) {
    cell_types.push_back(type);
    cell_nodes.insert(cell_nodes.end(), nodes.begin(), nodes.end());
    cell_offsets.push_back(int(cell_nodes.size()));
  }
  /// A straight polyline of `segments` equal segments from `a` to `b` (tests, benchmarks).
  static Mesh polyline(const Vec3& a, const Vec3& b, int segments);
  /// A regular nx x ny grid of quads (or, with `triangles`, each quad split along a diagonal)
  /// of spacing h in the x-y plane.
  static Mesh grid(int nx, int ny, double h, bool triangles = false);
};

/// The unique edges of the cells (line cells, triangle and quad sides), each as (min, max).
std::vector<std::pair<int, int>> mesh_edges(const Mesh& mesh);

/// Problems that make a mesh unusable, or "" when it is fine: a cell of an unknown type or with a
/// node index out of range or repeated, a zero-length edge, two nodes at the same place (relative
/// tolerance `tolerance` of the bounding-box diagonal), a node in no cell. The message names the
/// thing ("zero-length edge between nodes 3 and 4 at (0, 1, 0)"); node numbers are 0-based indices
/// unless `node_names` gives the file's own numbers.
std::string mesh_problem(const Mesh& mesh, double tolerance = 1e-9, const std::vector<long long>* node_names = nullptr);

}  // namespace pbd
