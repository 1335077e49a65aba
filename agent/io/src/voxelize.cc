// Voxelization: any gmsh geometry -> agents whose centres lie inside it, groups on the nearest staircase faces.
#include <agent/voxelize.h>

#include <Eigen/Geometry>
#include <gmsh.h>
#include <gmsh_session.h>
#include <gmsh_write.h>
#include <workbench/memory_limit.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>
#include <stdexcept>
#include <unordered_map>

namespace agent {

namespace {

namespace fs = std::filesystem;
using Eigen::Vector3d;

/// A facet of the body's boundary (a segment in 2D, a triangle in 3D) and the groups it is in.
struct Facet {
  std::array<Vector3d, 3> corner;
  int corners;
  const std::vector<std::string>* groups;
};

double segment_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (a + t * ab - p).norm();
}

double triangle_distance(const Vector3d& p, const Vector3d& a, const Vector3d& b, const Vector3d& c) {
  const Vector3d n = (b - a).cross(c - a);
  if (n.squaredNorm() > 0) {
    const Vector3d q = p - (p - a).dot(n) / n.squaredNorm() * n;  // p projected onto the plane
    const double u = (b - q).cross(c - q).dot(n), v = (c - q).cross(a - q).dot(n), w = (a - q).cross(b - q).dot(n);
    if (u >= 0 && v >= 0 && w >= 0) return (p - q).norm();
  }
  return std::min({segment_distance(p, a, b), segment_distance(p, b, c), segment_distance(p, c, a)});
}

double distance(const Vector3d& p, const Facet& f) {
  return f.corners == 2 ? segment_distance(p, f.corner[0], f.corner[1])
                        : triangle_distance(p, f.corner[0], f.corner[1], f.corner[2]);
}

}  // namespace

void write_staircase(const ImportedMesh& m, const fs::path& file) {
  const Grid& g = m.grid;
  const int dim = g.dim;
  gmsh::model::add("agent_staircase");
  const int body = gmsh::model::addDiscreteEntity(dim);
  // Lattice nodes used by an agent, tagged node_index + 1.
  std::vector<char> used(g.node_count(), 0);
  auto corner_node = [&](std::size_t cell, int corner) {
    static const int kQuad[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    const auto c = g.coords(cell);
    const int q = corner % 4, up = corner / 4;
    return g.node_index(c[0] + kQuad[q][0], c[1] + kQuad[q][1], c[2] + up);
  };
  const int corners = dim == 2 ? 4 : 8;
  std::vector<std::size_t> element_tags, element_nodes;
  for (std::size_t e = 0; e < m.cell_of_element.size(); ++e) {
    element_tags.push_back(e + 1);
    for (int k = 0; k < corners; ++k) {
      const std::size_t node = corner_node(m.cell_of_element[e], k);
      used[node] = 1;
      element_nodes.push_back(node + 1);
    }
  }
  std::vector<std::size_t> node_tags;
  std::vector<double> coords;
  for (std::size_t node = 0; node < g.node_count(); ++node)
    if (used[node]) {
      node_tags.push_back(node + 1);
      const auto p = g.node_coords(node);
      const Vector3d x = g.node_position(p[0], p[1], p[2]);
      coords.insert(coords.end(), {x[0], x[1], x[2]});
    }
  gmsh::model::mesh::addNodes(dim, body, node_tags, coords);
  gmsh::model::mesh::addElementsByType(body, dim == 2 ? 3 : 5, element_tags, element_nodes);
  gmsh::model::addPhysicalGroup(dim, {body}, 1);
  gmsh::model::setPhysicalName(dim, 1, "body");
  // One entity per group; a face is a 2-node line (2D) or a 4-node quadrangle (3D) of its corners.
  std::size_t next_tag = m.cell_of_element.size() + 1;
  int group_tag = 1;
  for (const auto& [name, faces] : m.face_groups) {
    const int entity = gmsh::model::addDiscreteEntity(dim - 1);
    std::vector<std::size_t> tags, nodes;
    for (const auto& f : faces) {
      const int a = axis_of(f.side), b = a == 0 ? 1 : 0, c = a == 2 ? 1 : 2;
      const auto p = g.coords(f.cell);
      std::array<int, 3> at = p;
      at[a] += is_positive(f.side) ? 1 : 0;
      auto node = [&](int db, int dc) {
        std::array<int, 3> q = at;
        q[b] += db;
        if (dim == 3) q[c] += dc;
        return g.node_index(q[0], q[1], q[2]) + 1;
      };
      tags.push_back(next_tag++);
      if (dim == 2) {
        nodes.insert(nodes.end(), {node(0, 0), node(1, 0)});
      } else {
        nodes.insert(nodes.end(), {node(0, 0), node(1, 0), node(1, 1), node(0, 1)});
      }
    }
    gmsh::model::mesh::addElementsByType(entity, dim == 2 ? 1 : 3, tags, nodes);
    gmsh::model::addPhysicalGroup(dim - 1, {entity}, group_tag);
    gmsh::model::setPhysicalName(dim - 1, group_tag++, name);
  }
  gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
  gmsh::option::setNumber("Mesh.SaveAll", 0);
  workbench::gmsh_write_checked(file);  // gmsh does not check its writes
}

namespace {

using Cell = std::array<std::int64_t, 3>;

/// The mesh's nodes by tag and their bounding box.
struct Nodes {
  std::unordered_map<std::size_t, Vector3d> at;
  Vector3d lo = Vector3d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
};

Nodes read_nodes(const std::string& name, int dim) {
  std::vector<std::size_t> node_tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(node_tags, xyz, parametric);
  if (node_tags.empty()) throw std::runtime_error(name + ": the mesh has no nodes");
  Nodes nodes;
  for (std::size_t i = 0; i < node_tags.size(); ++i) {
    const Vector3d x(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    if (!x.allFinite()) throw std::runtime_error(name + ": node " + std::to_string(node_tags[i]) + " is not finite");
    nodes.at[node_tags[i]] = x;
    nodes.lo = nodes.lo.cwiseMin(x);
    nodes.hi = nodes.hi.cwiseMax(x);
  }
  if (dim == 2 && nodes.hi[2] - nodes.lo[2] > 1e-12 * (nodes.hi - nodes.lo).norm())
    throw std::runtime_error(name + ": a 2D model must lie in the x-y plane");
  return nodes;
}

/// The lattice cells over the bounding box along each axis, in 64-bit lattice coordinates.
Cell lattice_cells(const Nodes& nodes, double size, int dim, const std::string& name) {
  Cell n{1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    const double along = std::max(1.0, std::ceil((nodes.hi[a] - nodes.lo[a]) / size - 1e-9));
    if (!(along < 1e15)) throw std::runtime_error(name + ": agent size " + std::to_string(size) + " m gives more than 1e15 agents along an axis");
    n[a] = std::int64_t(along);
  }
  return n;
}

/// Refuses a voxelization whose `slots` would not fit in memory.
void refuse_if_too_big(double slots, const char* what, double size, int dim, const std::string& name) {
  if (slots * study_bytes_per_slot(dim) <= workbench::memory_limit_bytes()) return;
  std::ostringstream s;
  s << name << ": agent size " << size << " m gives " << slots << " " << what << ", about "
    << slots * study_bytes_per_slot(dim) / workbench::kGiB << " GiB, more than the " << workbench::memory_limit_bytes() / workbench::kGiB
    << " GiB allowed (set WORKBENCH_MEMORY_LIMIT=<GiB> to raise it)";
  throw std::runtime_error(s.str());
}

/// The cells whose centre may lie in an element (its bounding box, one cell wider each way), in
/// grid order (k, then j, then i), each once; refused up front when they would not fit in memory.
std::vector<Cell> candidate_cells(const Nodes& nodes, const Cell& n, double size, int dim, const std::string& name) {
  std::vector<int> body_types;
  std::vector<std::vector<std::size_t>> body_tags, body_nodes;
  gmsh::model::mesh::getElements(body_types, body_tags, body_nodes, dim);
  std::vector<std::array<std::int64_t, 6>> element_boxes;  // lattice cells lo[0..2], hi[0..2] (inclusive)
  double candidates = 0;
  for (std::size_t t = 0; t < body_types.size(); ++t) {
    const std::size_t per = body_nodes[t].size() / std::max<std::size_t>(body_tags[t].size(), 1);
    for (std::size_t e = 0; e < body_tags[t].size(); ++e) {
      Vector3d elo = Vector3d::Constant(std::numeric_limits<double>::infinity()), ehi = -elo;
      for (std::size_t k = 0; k < per; ++k) {
        const Vector3d& x = nodes.at.at(body_nodes[t][e * per + k]);
        elo = elo.cwiseMin(x);
        ehi = ehi.cwiseMax(x);
      }
      std::array<std::int64_t, 6> box{0, 0, 0, 0, 0, 0};
      double cells = 1;
      for (int a = 0; a < dim; ++a) {
        box[a] = std::max<std::int64_t>(0, std::int64_t(std::floor((elo[a] - nodes.lo[a]) / size - 0.5)) - 1);
        box[3 + a] = std::min<std::int64_t>(n[a] - 1, std::int64_t(std::ceil((ehi[a] - nodes.lo[a]) / size - 0.5)) + 1);
        cells *= double(box[3 + a] - box[a] + 1);
      }
      candidates += cells;
      element_boxes.push_back(box);
    }
  }
  refuse_if_too_big(candidates, "agent slots to test", size, dim, name);
  std::vector<Cell> tried;
  tried.reserve(std::size_t(candidates));
  for (const auto& box : element_boxes)
    for (std::int64_t k = box[2]; k <= box[5]; ++k)
      for (std::int64_t j = box[1]; j <= box[4]; ++j)
        for (std::int64_t i = box[0]; i <= box[3]; ++i) tried.push_back({i, j, k});
  auto grid_order = [](const Cell& p, const Cell& q) { return std::tie(p[2], p[1], p[0]) < std::tie(q[2], q[1], q[0]); };
  std::sort(tried.begin(), tried.end(), grid_order);
  tried.erase(std::unique(tried.begin(), tried.end()), tried.end());
  return tried;
}

/// The cells whose centre lies inside an element of the body (strict search: no tolerance).
std::vector<Cell> cells_inside(const std::vector<Cell>& tried, const Vector3d& lo, double size, int dim) {
  std::vector<Cell> inside;
  std::vector<std::size_t> found;
  for (const Cell& l : tried) {
    Vector3d c = lo;
    for (int a = 0; a < dim; ++a) c[a] += (double(l[a]) + 0.5) * size;
    found.clear();
    try {
      gmsh::model::mesh::getElementsByCoordinates(c[0], c[1], dim == 3 ? c[2] : lo[2], found, dim, true);
    } catch (const std::string&) {  // gmsh 4.8 reports "no element found" by throwing its message
      found.clear();
    }
    if (!found.empty()) inside.push_back(l);
  }
  return inside;
}

/// The compressed lattice: the planes that hold agents and the bounding box's first and last, a
/// run of empty planes one air slot; the agents on it, every other slot air. Fills
/// out.cell_of_element (in (k, j, i) order, as `inside`).
Grid staircase_grid(const std::vector<Cell>& inside, const Cell& n, const Vector3d& lo, double size, int dim,
                    const std::string& name, ImportedMesh& out) {
  std::vector<CompressedAxis> axes;
  std::array<int, 3> cells{1, 1, 1};
  for (int a = 0; a < dim; ++a) {
    std::vector<std::int64_t> kept{0, n[a] - 1};
    for (const Cell& l : inside) kept.push_back(l[a]);
    axes.emplace_back(std::move(kept));
    if (!(axes[a].slots() < std::size_t(1e9)))
      throw std::runtime_error(name + ": agent size " + std::to_string(size) + " m gives more than 1e9 slots along an axis");
    cells[a] = int(axes[a].slots());
  }
  std::vector<std::array<int, 3>> agents(inside.size(), {0, 0, 0});
  for (std::size_t e = 0; e < inside.size(); ++e)
    for (int a = 0; a < dim; ++a) agents[e][a] = int(axes[a].slot(inside[e][a]));
  const double bytes = study_bytes(dim, cells, agents);
  if (!(bytes <= workbench::memory_limit_bytes())) {
    std::ostringstream s;
    s << name << ": agent size " << size << " m gives " << inside.size() << " agents in a compressed box of " << cells[0] << " x "
      << cells[1];
    if (dim == 3) s << " x " << cells[2];
    s << " slots, about " << bytes / workbench::kGiB << " GiB, more than the " << workbench::memory_limit_bytes() / workbench::kGiB
      << " GiB allowed (set WORKBENCH_MEMORY_LIMIT=<GiB> to raise it)";
    throw std::runtime_error(s.str());
  }
  Grid grid = Grid::lattice(dim, {&axes[0], &axes[1], dim == 3 ? &axes[2] : nullptr}, lo,
                            Vector3d(size, size, dim == 3 ? size : 1.0), agents);
  for (const auto& c : agents) out.cell_of_element.push_back(grid.index(c[0], c[1], c[2]));
  return grid;
}

/// The facets of the body's boundary, each with the physical groups of its entity.
struct BodyBoundary {
  std::map<int, std::vector<std::string>> groups_of_entity;  ///< the facets point into it
  std::vector<Facet> facets;
};

void read_boundary(const Nodes& nodes, int dim, BodyBoundary& out) {
  gmsh::vectorpair bodies, boundary;
  gmsh::model::getEntities(bodies, dim);
  gmsh::model::getBoundary(bodies, boundary, true, false, false);
  for (const auto& [d, signed_tag] : boundary) {
    const int tag = std::abs(signed_tag);
    auto& names = out.groups_of_entity[tag];
    std::vector<int> physical;
    gmsh::model::getPhysicalGroupsForEntity(d, tag, physical);
    for (int p : physical) {
      std::string group;
      gmsh::model::getPhysicalName(d, p, group);
      names.push_back(group.empty() ? std::to_string(p) : group);
    }
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> tags, element_nodes;
    gmsh::model::mesh::getElements(types, tags, element_nodes, d, tag);
    for (std::size_t t = 0; t < types.size(); ++t) {
      std::string type_name;
      int edim, order, per, primary;
      std::vector<double> local;
      gmsh::model::mesh::getElementProperties(types[t], type_name, edim, order, per, local, primary);
      for (std::size_t e = 0; e < tags[t].size(); ++e) {
        auto x = [&](int k) { return nodes.at.at(element_nodes[t][e * per + k]); };
        if (d == 1) {
          out.facets.push_back({{x(0), x(1), x(1)}, 2, &names});
        } else {  // triangles, and quadrangles as two triangles
          out.facets.push_back({{x(0), x(1), x(2)}, 3, &names});
          if (primary == 4) out.facets.push_back({{x(0), x(2), x(3)}, 3, &names});
        }
      }
    }
  }
}

/// Every boundary group (even if no face lands in it); each staircase boundary face joins the
/// groups of the facet nearest to its centre.
void assign_groups(const Grid& grid, const BodyBoundary& boundary, ImportedMesh& out) {
  for (const auto& [tag, names] : boundary.groups_of_entity)
    for (const auto& group : names) out.face_groups[group];
  for (const auto& f : grid.boundary_faces()) {
    Vector3d centre = grid.centre(f.cell);
    centre[axis_of(f.side)] += (is_positive(f.side) ? 0.5 : -0.5) * grid.size[axis_of(f.side)];
    double best = std::numeric_limits<double>::infinity();
    const Facet* nearest = nullptr;
    for (const auto& facet : boundary.facets) {
      const double dist = distance(centre, facet);
      if (dist < best) {
        best = dist;
        nearest = &facet;
      }
    }
    if (nearest)
      for (const auto& group : *nearest->groups) out.face_groups[group].push_back(f);
  }
}

}  // namespace

ImportedMesh voxelize(const fs::path& geometry, double size, const std::map<std::string, double>& parameters,
                      const fs::path& staircase_msh, double unit) {
  const std::string name = geometry.string();
  if (!(size > 0) || !std::isfinite(size)) throw std::runtime_error(name + ": the agent size must be a number > 0");
  ImportedMesh out;
  out.parameters = workbench::gmsh_load(geometry, parameters, unit);
  const int dim = gmsh::model::getDimension();
  if (dim != 2 && dim != 3) throw std::runtime_error(name + ": the model must be 2D or 3D");
  const Nodes nodes = read_nodes(name, dim);
  // The lattice over the bounding box: the cells that may hold an agent, those that do.
  const Cell n = lattice_cells(nodes, size, dim, name);
  const auto inside = cells_inside(candidate_cells(nodes, n, size, dim, name), nodes.lo, size, dim);
  if (inside.empty())
    throw std::runtime_error(name + ": no agent of size " + std::to_string(size) + " m has its centre inside the body");
  Grid grid = staircase_grid(inside, n, nodes.lo, size, dim, name, out);
  BodyBoundary boundary;
  read_boundary(nodes, dim, boundary);
  assign_groups(grid, boundary, out);
  out.grid = std::move(grid);
  if (!staircase_msh.empty()) write_staircase(out, staircase_msh);
  return out;
}

}  // namespace agent
