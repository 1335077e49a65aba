// The agent grid from a gmsh mesh of equal squares or cubes (gmsh API, the one place agent meets gmsh).
#include <agent/mesh_import.h>

#include <gmsh.h>
#include <gmsh_session.h>
#include <workbench/memory_limit.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>
#include <unordered_map>


namespace agent {

namespace {

namespace fs = std::filesystem;

struct MeshError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What fixes a mesh that is not the agents' lattice: the voxelization (docs/agent-model.md).
const std::string kVoxelizeHint =
    "; for a body of any shape give [mesh] agent_size [m] (voxelized in the run) or make a .msh with "
    "`workbench voxelize` (docs/agent-model.md, \"Voxelization\")";

}  // namespace

std::string point_text(const Eigen::Vector3d& x, int dim) {
  std::ostringstream s;
  s << "(" << x[0] << ", " << x[1];
  if (dim == 3) s << ", " << x[2];
  s << ")";
  return s.str();
}

double study_bytes_per_slot(int dim) {
  // Solver: 2 dim face forces and a generation per slot, the grid's flag byte; study: stress,
  // strain, displacement and output points, import tables (measured sizes, rounded up).
  return dim == 2 ? 200.0 : 300.0;
}

double study_bytes(int dim, const std::array<int, 3>& cells, const std::vector<std::array<int, 3>>& agents) {
  const LatticeLayout layout = lattice_layout(dim, cells, agents);
  double bytes = layout.slots * study_bytes_per_slot(dim);
  if (layout.tiled) {
    const double box = double(cells[0]) * cells[1] * cells[2];
    double layer = 0;
    for (int a = 0; a < dim; ++a) layer = std::max(layer, box / cells[a]);
    bytes += 4 * layout.tile_table + 3 * 8 * layer;
  }
  return bytes;
}

namespace {

/// The model's elements of its own dimension as gmsh gives them: equal squares (4-node
/// quadrangles) or cubes (8-node hexahedra), else a MeshError.
struct GmshElements {
  int dim = 2, corners = 4;
  std::unordered_map<std::size_t, Eigen::Vector3d> node_at;  ///< node tag -> position
  std::vector<std::size_t> tags;   ///< element tags
  std::vector<std::size_t> nodes;  ///< corners node tags per element
  std::size_t count() const { return tags.size(); }
  const Eigen::Vector3d& corner(std::size_t e, int c) const { return node_at.at(nodes[e * corners + c]); }
  std::string element(std::size_t e) const { return "element " + std::to_string(tags[e]); }
};

GmshElements read_elements(const std::string& name) {
  GmshElements m;
  m.dim = gmsh::model::getDimension();
  const int dim = m.dim;
  if (dim != 2 && dim != 3) throw MeshError(name + ": the model must be 2D or 3D (got dimension " + std::to_string(dim) + ")");

  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric);
  m.node_at.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    m.node_at[node_tags[i]] = Eigen::Vector3d(coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]);

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, dim);
  const int wanted = dim == 2 ? 3 : 5;  // 4-node quadrangle, 8-node hexahedron
  m.corners = dim == 2 ? 4 : 8;
  for (int t : types)
    if (t != wanted) {
      std::string type_name;
      int d, order, nn, np;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(t, type_name, d, order, nn, local, np);
      throw MeshError(name + ": has " + type_name + " elements; the agent method needs a structured mesh of " +
                      (dim == 2 ? "4-node squares" : "8-node cubes") + " (Transfinite + Recombine)" + kVoxelizeHint);
    }
  if (types.empty()) throw MeshError(name + ": holds no " + std::to_string(dim) + "D elements");
  m.nodes = std::move(element_nodes[0]);
  m.tags = std::move(element_tags[0]);
  return m;
}

/// Each element's lower corner, their common size and the bounding box of them all.
struct ElementBoxes {
  std::vector<Eigen::Vector3d> lo;
  Eigen::Vector3d size = Eigen::Vector3d::Ones();
  Eigen::Vector3d lo_all = Eigen::Vector3d::Constant(1e300), hi_all = Eigen::Vector3d::Constant(-1e300);
};

/// Bounding box of each element: all equal, axis aligned, corners at the box's corners.
ElementBoxes element_boxes(const GmshElements& m, const std::string& name) {
  const int dim = m.dim;
  ElementBoxes b;
  b.lo.resize(m.count());
  Eigen::Vector3d& size = b.size;
  for (std::size_t e = 0; e < m.count(); ++e) {
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = Eigen::Vector3d::Constant(-1e300);
    for (int c = 0; c < m.corners; ++c) {
      const Eigen::Vector3d& x = m.corner(e, c);
      lo = lo.cwiseMin(x);
      hi = hi.cwiseMax(x);
    }
    const Eigen::Vector3d s = hi - lo;
    if (e == 0) {
      size = s;
      for (int a = 0; a < dim; ++a)
        if (!(size[a] > 0)) throw MeshError(name + ": " + m.element(e) + " is degenerate");
      if (dim == 2 && std::abs(s[2]) > 1e-12 * size.head<2>().norm())
        throw MeshError(name + ": a 2D mesh must lie in the x-y plane");
    }
    const double tol = 1e-6 * size.head(dim).minCoeff();
    for (int a = 0; a < dim; ++a)
      if (std::abs(s[a] - size[a]) > tol)
        throw MeshError(name + ": agents must all be the same size; " + m.element(e) + " at " + point_text(lo, dim) +
                        " differs (structured mesh with uniform spacing needed)" + kVoxelizeHint);
    for (int c = 0; c < m.corners; ++c) {
      const Eigen::Vector3d& x = m.corner(e, c);
      for (int a = 0; a < dim; ++a)
        if (std::min(std::abs(x[a] - lo[a]), std::abs(x[a] - hi[a])) > tol)
          throw MeshError(name + ": " + m.element(e) +
                          " is not an axis-aligned square/cube; the agent method needs a grid aligned with x, y" +
                          (dim == 3 ? ", z" : "") + kVoxelizeHint);
    }
    b.lo[e] = lo;
    b.lo_all = b.lo_all.cwiseMin(lo);
    b.hi_all = b.hi_all.cwiseMax(hi);
  }
  if (dim == 2) size[2] = 1.0;
  return b;
}

/// The lattice the agents lie on: coordinates (64-bit, agent sizes from the lower corner) of every
/// element, the compressed axes (only the planes that hold agents, a run of empty planes one air
/// slot) and each element's slot, found before any box is allocated.
struct Lattice {
  std::vector<CompressedAxis> axes;
  std::array<int, 3> cells{1, 1, 1};
  std::vector<std::array<int, 3>> slot_of_element;
};

/// The lattice coordinate of x along axis a, else a MeshError naming `what`.
std::int64_t lattice_coordinate(const ElementBoxes& b, const std::string& name, double x, int a, const std::string& what) {
  const double tol = 1e-4;
  const double f = (x - b.lo_all[a]) / b.size[a];
  if (!(std::abs(f) < 1e15)) throw MeshError(name + ": " + what + " lies more than 1e15 agent sizes from the others");
  const std::int64_t l = std::llround(f);
  if (std::abs(f - double(l)) > tol) throw MeshError(name + ": " + what + " is off the agent grid (uneven spacing)" + kVoxelizeHint);
  return l;
}

Lattice element_lattice(const GmshElements& m, const ElementBoxes& b, const std::string& name) {
  const int dim = m.dim;
  const std::size_t n_elements = m.count();
  std::vector<std::array<std::int64_t, 3>> element_at(n_elements, {0, 0, 0});
  std::array<std::vector<std::int64_t>, 3> occupied;
  for (std::size_t e = 0; e < n_elements; ++e)
    for (int a = 0; a < dim; ++a) {
      element_at[e][a] = lattice_coordinate(b, name, b.lo[e][a], a, m.element(e));
      occupied[a].push_back(element_at[e][a]);
    }
  Lattice l;
  for (int a = 0; a < dim; ++a) l.axes.emplace_back(std::move(occupied[a]));
  double longest = 1;
  for (int a = 0; a < dim; ++a) {
    longest = std::max(longest, double(l.axes[a].slots()));
    l.cells[a] = int(std::min(l.axes[a].slots(), std::size_t(1) << 30));
  }
  if (!(longest < 1e9)) {
    std::ostringstream s;
    s << name << ": the agent grid has " << longest << " slots along an axis (bounding box "
      << point_text(b.hi_all - b.lo_all, dim) << " m, agents of " << b.size[0] << " m), more than 1e9";
    throw MeshError(s.str());
  }
  l.slot_of_element.assign(n_elements, {0, 0, 0});
  for (std::size_t e = 0; e < n_elements; ++e)
    for (int a = 0; a < dim; ++a) l.slot_of_element[e][a] = int(l.axes[a].slot(element_at[e][a]));
  return l;
}

/// Refuses up front a body that would not fit in memory (its stored slots: the compressed box, or
/// the tiles its agents touch).
void check_memory(const GmshElements& m, const ElementBoxes& b, const Lattice& l, const std::string& name) {
  const int dim = m.dim;
  const auto& cells = l.cells;
  const double estimate = study_bytes(dim, cells, l.slot_of_element);
  const double limit = workbench::memory_limit_bytes();
  if (!(estimate <= limit)) {
    std::ostringstream s;
    s << name << ": the agent grid (" << m.count() << " agents of " << b.size[0] << " m in a compressed box of " << cells[0]
      << " x " << cells[1];
    if (dim == 3) s << " x " << cells[2];
    s << " slots, bounding box " << point_text(b.hi_all - b.lo_all, dim) << " m) needs about " << estimate / workbench::kGiB
      << " GiB, more than the " << limit / workbench::kGiB
      << " GiB allowed (the machine's memory; set WORKBENCH_MEMORY_LIMIT=<GiB> to raise it)";
    throw MeshError(s.str());
  }
}

/// Places every element in its slot (a second element in a slot is an overlap), filling
/// out.cell_of_element; returns the grid node of every node tag. Neighbours come from the mesh:
/// agents that share a face must share its nodes.
std::unordered_map<std::size_t, std::size_t> place_elements(const GmshElements& m, const ElementBoxes& b,
                                                            const Lattice& l, const Grid& grid, const std::string& name,
                                                            ImportedMesh& out) {
  const int dim = m.dim;
  // Plane index of lattice coordinate c: a slot's first coordinate or the end of the box.
  auto plane_of = [&](std::int64_t c, int a, const std::string& what) {
    const auto& first = l.axes[a].first;
    const auto it = std::lower_bound(first.begin(), first.end(), c);
    if (it == first.end() || *it != c) throw MeshError(name + ": " + what + " is not a corner of its element's lattice cell");
    return int(it - first.begin());
  };
  out.cell_of_element.resize(m.count());
  std::vector<std::size_t> element_in(grid.count(), std::size_t(-1));
  std::unordered_map<std::size_t, std::size_t> grid_node_of_tag;
  std::vector<std::size_t> tag_at_node(grid.node_count(), 0);
  for (std::size_t e = 0; e < m.count(); ++e) {
    const auto& c = l.slot_of_element[e];
    const std::size_t cell = grid.index(c[0], c[1], c[2]);
    if (element_in[cell] != std::size_t(-1))
      throw MeshError(name + ": elements " + std::to_string(m.tags[element_in[cell]]) + " and " +
                      std::to_string(m.tags[e]) + " overlap at " + point_text(b.lo[e], dim));
    element_in[cell] = e;
    out.cell_of_element[e] = cell;
    for (int k = 0; k < m.corners; ++k) {
      const std::size_t tag = m.nodes[e * m.corners + k];
      const Eigen::Vector3d& x = m.node_at.at(tag);
      std::array<int, 3> p{0, 0, 0};
      for (int a = 0; a < dim; ++a) {
        const std::string what = "node " + std::to_string(tag);
        p[a] = plane_of(lattice_coordinate(b, name, x[a], a, what), a, what);
      }
      // A node is a corner of its element's slot (plane_of passed); that slot's corners are stored.
      const std::size_t node = grid.node_index(p[0], p[1], p[2]);
      if (tag_at_node[node] != 0 && tag_at_node[node] != tag)
        throw MeshError(name + ": nodes " + std::to_string(tag_at_node[node]) + " and " + std::to_string(tag) +
                        " coincide at " + point_text(x, dim) + "; neighbouring agents must share nodes (Coherence)");
      tag_at_node[node] = tag;
      grid_node_of_tag[tag] = node;
    }
  }
  return grid_node_of_tag;
}

/// The physical groups of dimension dim-1 as outer faces: each face belongs to the agent on one
/// side of it and must have air (or the box's outside) on the other.
void read_face_groups(const Grid& grid, const std::unordered_map<std::size_t, std::size_t>& grid_node_of_tag,
                      const std::string& name, ImportedMesh& out) {
  const int dim = grid.dim;
  for (const auto& [group, elements] : workbench::gmsh_physical_groups(dim - 1)) {
    auto& faces = out.face_groups[group];
    for (const auto& element : elements) {
      if (element.type != (dim == 2 ? 1 : 3))
        throw MeshError(name + ": physical group '" + group + "' holds elements that are not " +
                        (dim == 2 ? "2-node lines" : "4-node quadrangles"));
      std::array<int, 3> lo{1 << 30, 1 << 30, 1 << 30}, hi{-1, -1, -1};
      for (std::size_t tag : element.nodes) {
        auto it = grid_node_of_tag.find(tag);
        if (it == grid_node_of_tag.end())
          throw MeshError(name + ": physical group '" + group + "' has a face whose nodes belong to no agent");
        const auto p = grid.node_coords(it->second);
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::min(lo[a], p[a]);
          hi[a] = std::max(hi[a], p[a]);
        }
      }
      // The face is normal to the axis its nodes share.
      int axis = -1;
      for (int a = 0; a < dim; ++a)
        if (lo[a] == hi[a]) axis = a;
      if (axis < 0) throw MeshError(name + ": physical group '" + group + "' has a degenerate face");
      std::array<int, 3> below = lo, above = lo;
      below[axis] -= 1;
      if (dim == 2) below[2] = above[2] = 0;
      auto agent_at = [&](const std::array<int, 3>& c) {
        if (c[axis] < 0 || c[axis] >= grid.cells[axis]) return false;
        const std::size_t cell = grid.index(c[0], c[1], c[2]);
        return cell != Grid::npos && !grid.is_air(cell);
      };
      const bool has_below = agent_at(below), has_above = agent_at(above);
      if (has_below && has_above)
        throw MeshError(name + ": physical group '" + group +
                        "' has a face inside the body; loads and supports act on faces toward air only");
      if (has_below)
        faces.push_back({grid.index(below[0], below[1], below[2]), direction(axis, true)});
      else if (has_above)
        faces.push_back({grid.index(above[0], above[1], above[2]), direction(axis, false)});
      else
        throw MeshError(name + ": physical group '" + group + "' has a face whose nodes belong to no agent");
    }
  }
}

}  // namespace

ImportedMesh import_mesh(const fs::path& file, const std::map<std::string, double>& parameters, double unit) {
  const std::string name = file.string();
  ImportedMesh out;
  try {
    out.parameters = workbench::gmsh_load(file, parameters, unit);
  } catch (const std::runtime_error& e) {
    throw MeshError(e.what());
  }
  const auto elements = read_elements(name);
  const auto boxes = element_boxes(elements, name);
  const auto lattice = element_lattice(elements, boxes, name);
  check_memory(elements, boxes, lattice, name);
  // Every slot no element fills is air.
  const int dim = elements.dim;
  const auto& axes = lattice.axes;
  Grid grid = Grid::lattice(dim, {&axes[0], &axes[1], dim == 3 ? &axes[2] : nullptr}, boxes.lo_all, boxes.size,
                            lattice.slot_of_element);
  const auto grid_node_of_tag = place_elements(elements, boxes, lattice, grid, name, out);
  read_face_groups(grid, grid_node_of_tag, name, out);
  out.grid = std::move(grid);
  return out;
}

}  // namespace agent
