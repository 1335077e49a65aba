// gmsh -> PlainMesh: the same .geo files and ONELAB parameters as the agent's mesh import, read
// through the gmsh API. Element order = gmsh::model::mesh::getElements order.
#include "plain_mesh.h"

#include <fem_reference/mpi.h>
#include <workbench/error.h>

#include <gmsh.h>
#include <gmsh_session.h>

#include <algorithm>
#include <array>
#include <functional>
#include <cmath>
#include <unordered_map>

namespace fem_reference {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

struct TypeInfo {
  int dim;
  bool simplex;
  int corners;
  std::vector<int> to_deal;  // deal.II vertex k = gmsh vertex to_deal[k]
};

/// The element types deal.II reads here: first-order quads, hexes, triangles, tetrahedra.
const TypeInfo* type_info(int type) {
  static const std::map<int, TypeInfo> types{
      {3, {2, false, 4, {0, 1, 3, 2}}},
      {5, {3, false, 8, {0, 1, 3, 2, 4, 5, 7, 6}}},
      {2, {2, true, 3, {0, 1, 2}}},
      {4, {3, true, 4, {0, 1, 2, 3}}},
  };
  auto it = types.find(type);
  return it == types.end() ? nullptr : &it->second;
}

std::string type_name(int type) {
  std::string name;
  int d, order, nn, np;
  std::vector<double> local;
  gmsh::model::mesh::getElementProperties(type, name, d, order, nn, local, np);
  return name;
}

}  // namespace

PlainMesh read_gmsh_mesh(const fs::path& file, const std::map<std::string, double>& parameters, double unit) {
  const std::string name = file.string();
  // The one gmsh loader of the process (common/gmsh), shared with the agent and PBD readers. Every
  // rank loads the mesh (a .geo in a child process, which may fail on one rank only): a failure on
  // any rank ends every rank with the same message.
  mpi_collective([&] { workbench::gmsh_load(file, parameters, unit); });

  PlainMesh mesh;
  mesh.source = name;
  const int dim = gmsh::model::getDimension();
  if (dim != 2 && dim != 3) throw Error(name + ": the model must be 2D or 3D (got dimension " + std::to_string(dim) + ")");
  mesh.dim = dim;

  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, element_nodes;
  gmsh::model::mesh::getElements(types, element_tags, element_nodes, dim);
  if (types.empty()) throw Error(name + ": holds no " + std::to_string(dim) + "D elements");
  for (int t : types) {
    const TypeInfo* info = type_info(t);
    if (!info || info->dim != dim)
      throw Error(name + ": has " + type_name(t) + " elements, which the FEM reference cannot read (it reads " +
                  (dim == 2 ? "4-node quadrangles or 3-node triangles" : "8-node hexahedra or 4-node tetrahedra") +
                  ")");
  }
  if (types.size() > 1)
    throw Error(name + ": mixes " + type_name(types[0]) + " and " + type_name(types[1]) +
                " elements; the FEM reference reads one element type per mesh");
  const TypeInfo& info = *type_info(types[0]);
  mesh.simplex = info.simplex;
  mesh.corners = info.corners;

  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(node_tags, coords, parametric);
  // Nodes of the cells only, in gmsh node order.
  std::unordered_map<std::size_t, std::size_t> position;
  position.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i) position.emplace(node_tags[i], i);
  std::vector<char> used(node_tags.size(), 0);
  for (std::size_t tag : element_nodes[0]) used[position.at(tag)] = 1;
  std::unordered_map<std::size_t, unsigned> index_of_tag;
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    if (used[i]) {
      index_of_tag.emplace(node_tags[i], unsigned(mesh.node_count()));
      mesh.nodes.insert(mesh.nodes.end(), {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]});
    }
  if (dim == 2) {
    double zmax = 0, size = 0;
    for (std::size_t i = 0; i < mesh.node_count(); ++i) {
      zmax = std::max(zmax, std::abs(mesh.nodes[3 * i + 2] - mesh.nodes[2]));
      size = std::max({size, std::abs(mesh.nodes[3 * i]), std::abs(mesh.nodes[3 * i + 1])});
    }
    if (zmax > 1e-12 * std::max(size, 1e-300)) throw Error(name + ": a 2D mesh must lie in the x-y plane");
  }
  const std::size_t n_cells = element_tags[0].size();
  mesh.cells.resize(n_cells * info.corners);
  for (std::size_t e = 0; e < n_cells; ++e)
    for (int k = 0; k < info.corners; ++k)
      mesh.cells[e * info.corners + k] = index_of_tag.at(element_nodes[0][e * info.corners + info.to_deal[k]]);

  // Physical groups of dimension dim-1.
  for (const auto& [group, elements] : workbench::gmsh_physical_groups(dim - 1)) {
    auto& faces = mesh.face_groups[group];
    for (const auto& element : elements) {
      if (element.type != 1 && element.type != 2 && element.type != 3)
        throw Error(name + ": physical group '" + group + "' holds " + type_name(element.type) +
                    " elements, which the FEM reference cannot read");
      std::vector<unsigned> face;
      for (std::size_t tag : element.nodes) {
        auto it = index_of_tag.find(tag);
        if (it == index_of_tag.end())
          throw Error(name + ": physical group '" + group + "' has a face whose nodes belong to no element");
        face.push_back(it->second);
      }
      faces.push_back(std::move(face));
    }
  }
  return mesh;
}

PlainMesh box_mesh(const Box& box) {
  PlainMesh mesh;
  mesh.source = "box";
  mesh.dim = box.cells[2] > 0 ? 3 : 2;
  const int dim = mesh.dim;
  mesh.corners = dim == 2 ? 4 : 8;
  std::array<int, 3> n{box.cells[0], box.cells[1], dim == 3 ? box.cells[2] : 0};
  for (int a = 0; a < dim; ++a)
    if (n[a] < 1 || !(box.hi[a] > box.lo[a])) throw Error("box: needs at least one cell and hi > lo on every axis");
  const int nx = n[0] + 1, ny = n[1] + 1, nz = n[2] + 1;
  auto node = [&](int i, int j, int k) { return unsigned((k * ny + j) * nx + i); };
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        mesh.nodes.insert(mesh.nodes.end(),
                          {box.lo[0] + (box.hi[0] - box.lo[0]) * i / n[0], box.lo[1] + (box.hi[1] - box.lo[1]) * j / n[1],
                           dim == 3 ? box.lo[2] + (box.hi[2] - box.lo[2]) * k / n[2] : 0.0});
  for (int k = 0; k < std::max(n[2], 1); ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        for (int c = 0; c < mesh.corners; ++c)
          mesh.cells.push_back(node(i + (c & 1), j + ((c >> 1) & 1), k + ((c >> 2) & 1)));
      }
  const char* names[3][2] = {{"x0", "x1"}, {"y0", "y1"}, {"z0", "z1"}};
  for (int a = 0; a < dim; ++a)
    for (int s = 0; s < 2; ++s) {
      auto& faces = mesh.face_groups[names[a][s]];
      const int b = (a + 1) % dim, c = (a + 2) % dim;
      const int nb = n[b], nc = dim == 3 ? n[c] : 1;
      for (int q = 0; q < nc; ++q)
        for (int p = 0; p < nb; ++p) {
          std::vector<unsigned> face;
          const int corners = dim == 2 ? 2 : 4;
          for (int v = 0; v < corners; ++v) {
            std::array<int, 3> ijk{0, 0, 0};
            ijk[a] = s * n[a];
            ijk[b] = p + (v & 1);
            if (dim == 3) ijk[c] = q + ((v >> 1) & 1);
            face.push_back(node(ijk[0], ijk[1], ijk[2]));
          }
          faces.push_back(face);
        }
    }
  return mesh;
}

double slenderness(const PlainMesh& mesh) {
  std::array<double, 3> lo{1e308, 1e308, 1e308}, hi{-1e308, -1e308, -1e308};
  for (std::size_t i = 0; i < mesh.node_count(); ++i)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], mesh.nodes[3 * i + a]);
      hi[a] = std::max(hi[a], mesh.nodes[3 * i + a]);
    }
  std::array<double, 3> side{};
  for (int a = 0; a < mesh.dim; ++a) side[a] = hi[a] - lo[a];
  std::sort(side.begin(), side.end(), std::greater<>());
  return side[1] > 0 ? side[0] / side[1] : 1.0;
}

int normal_axis(const PlainMesh& mesh, const std::string& group) {
  const auto& faces = mesh.face_groups.at(group);
  int axis = -1;
  for (const auto& face : faces) {
    int found = -1;
    for (int a = 0; a < mesh.dim && found < 0; ++a) {
      double lo = 1e308, hi = -1e308, extent = 0;
      for (unsigned v : face) {
        lo = std::min(lo, mesh.nodes[3 * v + a]);
        hi = std::max(hi, mesh.nodes[3 * v + a]);
      }
      for (int b = 0; b < mesh.dim; ++b) {
        double l = 1e308, h = -1e308;
        for (unsigned v : face) {
          l = std::min(l, mesh.nodes[3 * v + b]);
          h = std::max(h, mesh.nodes[3 * v + b]);
        }
        extent = std::max(extent, h - l);
      }
      if (hi - lo <= 1e-9 * extent) found = a;
    }
    if (found < 0 || (axis >= 0 && found != axis)) return -1;
    axis = found;
  }
  return axis;
}

}  // namespace fem_reference
