// FEM results sampled onto the agent grid by point location.
#include <compare/sampling.h>

#include <compare/metrics.h>
#include <workbench/error.h>

#include <algorithm>
#include <cmath>

namespace compare {

using workbench::Error;

namespace {

/// Grid index along each axis of the cell holding `p` (-1 when outside the grid's box).
bool locate_cell(const agent::Grid& g, const double* p, int idx[3]) {
  idx[0] = idx[1] = idx[2] = 0;
  for (int a = 0; a < g.dim; ++a) {
    const double f = g.slot_coordinate(a, p[a]);
    if (!(f >= 0 && f < g.cells[a])) return false;
    idx[a] = int(std::floor(f));
  }
  return true;
}

/// Grid node at `p` (within 1e-6 agent sizes), if there is one.
bool locate_node(const agent::Grid& g, const double* p, int idx[3]) {
  idx[0] = idx[1] = idx[2] = 0;
  for (int a = 0; a < g.dim; ++a) {
    const double f = g.slot_coordinate(a, p[a]);
    if (!(f > -0.5 && f < g.cells[a] + 0.5)) return false;
    idx[a] = int(std::lround(f));
    if (std::abs(f - idx[a]) > 1e-6) return false;
    if (g.compressed() && std::abs(p[a] - g.plane(a, idx[a])) > 1e-6 * g.size[a]) return false;  // beside a wide air slot
  }
  return true;
}

}  // namespace

GridFields fem_on_grid(const agent::ImportedMesh& mesh, const fem_reference::FemResult& fem,
                       const std::string& case_name) {
  const auto& grid = mesh.grid;
  const int dim = grid.dim;
  if (fem.dim != dim) throw Error(case_name + ": the FEM mesh is " + std::to_string(fem.dim) + "D, the agents " +
                                  std::to_string(dim) + "D");
  GridFields out;
  out.stress.assign(grid.count() * kStressSlots, 0.0);
  std::vector<int> hits(grid.count(), 0);
  const std::vector<double>* components[6] = {&fem.sigma_x, &fem.sigma_y, &fem.sigma_z,
                                              &fem.tau_xy,  &fem.tau_yz,  &fem.tau_xz};
  for (std::size_t e = 0; e < fem.cell_count(); ++e) {
    int c[3];
    if (!locate_cell(grid, &fem.cell_centres[3 * e], c)) continue;
    const std::size_t cell = grid.index(c[0], c[1], c[2]);
    if (cell == agent::Grid::npos) continue;  // a tiled grid's unstored tile: air
    for (int k = 0; k < 6; ++k) out.stress[kStressSlots * cell + k] += (*components[k])[e];
    ++hits[cell];
  }
  for (std::size_t cell : mesh.cell_of_element) {
    if (hits[cell] == 0)
      throw Error(case_name + ": no FEM cell centre lies in agent " + std::to_string(cell) +
                  " (the FEM mesh does not cover the agents' body, or its cells are larger than the agents)");
    double* s = &out.stress[kStressSlots * cell];
    for (int k = 0; k < 6; ++k) s[k] /= hits[cell];
    s[kVonMises] = von_mises(s);  // of the agent's mean stress, as for the agents' own
  }
  out.u.assign(grid.node_count() * dim, 0.0);
  std::vector<char> found(grid.node_count(), 0);
  for (std::size_t n = 0; n < fem.node_count(); ++n) {
    int p[3];
    if (!locate_node(grid, &fem.node_points[3 * n], p)) continue;
    const std::size_t node = grid.node_index(p[0], p[1], p[2]);
    if (node == agent::Grid::npos) continue;  // no agent's corner
    for (int a = 0; a < dim; ++a) out.u[node * dim + a] = fem.node_displacement[n * dim + a];
    found[node] = 1;
  }
  // Every corner of every agent of the body must have been found.
  for (std::size_t cell : mesh.cell_of_element) {
    const auto c = grid.coords(cell);
    for (int corner = 0; corner < (1 << dim); ++corner) {
      const std::size_t node = grid.node_index(c[0] + (corner & 1), c[1] + ((corner >> 1) & 1),
                                               c[2] + (dim == 3 ? (corner >> 2) & 1 : 0));
      if (!found[node])
        throw Error(case_name + ": the FEM mesh has no node at a corner of agent " + std::to_string(cell) +
                    " (the reference must have the agent nodes among its nodes)");
    }
  }
  return out;
}

std::vector<std::array<double, 3>> agent_probe_points(const agent::Grid& grid) {
  std::vector<std::array<double, 3>> points;
  const double g = 0.5 / std::sqrt(3.0);  // the 2-point Gauss rule on [-1/2, 1/2]
  for (std::size_t cell = 0; cell < grid.count(); ++cell)
    if (!grid.is_air(cell)) {
      const Eigen::Vector3d c = grid.centre(cell);
      for (int corner = 0; corner < (1 << grid.dim); ++corner) {
        std::array<double, 3> p{0, 0, 0};
        for (int a = 0; a < grid.dim; ++a) p[a] = c[a] + ((corner >> a) & 1 ? g : -g) * grid.size[a];
        points.push_back(p);
      }
    }
  for (std::size_t node : body_node_ids(grid)) {
    const auto n = grid.node_coords(node);
    const Eigen::Vector3d x = grid.node_position(n[0], n[1], n[2]);
    points.push_back({x[0], x[1], grid.dim == 3 ? x[2] : 0.0});
  }
  return points;
}

GridFields fem_at_agents(const agent::Grid& grid, const fem_reference::FemResult& fem, std::array<std::size_t, 2>& outside) {
  const auto points = agent_probe_points(grid);
  if (fem.probes.size() != points.size()) throw Error("compare: the FEM result was not evaluated at the agents");
  const int dim = grid.dim;
  auto nearest_element = [&](const std::array<double, 3>& p) {
    std::size_t best = 0;
    double best_d2 = INFINITY;
    for (std::size_t e = 0; e < fem.cell_count(); ++e) {
      double d2 = 0;
      for (int a = 0; a < 3; ++a) d2 += std::pow(fem.cell_centres[3 * e + a] - p[a], 2);
      if (d2 < best_d2) best_d2 = d2, best = e;
    }
    return best;
  };
  GridFields out;
  out.stress.assign(grid.count() * kStressSlots, 0.0);
  out.u.assign(grid.node_count() * dim, 0.0);
  outside = {0, 0};
  std::size_t at = 0;
  const int gauss = 1 << dim;
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    if (grid.is_air(cell)) continue;
    int found = 0;
    for (int q = 0; q < gauss; ++q) {
      const auto& probe = fem.probes[at + q];
      if (!probe.found) continue;
      double* s = &out.stress[kStressSlots * cell];
      for (int k = 0; k < 6; ++k) s[k] += probe.sigma[k];
      ++found;
    }
    double* s = &out.stress[kStressSlots * cell];
    if (found > 0) {
      for (int k = 0; k < 6; ++k) s[k] /= found;
      s[kVonMises] = von_mises(s);
    } else {  // the whole agent lies outside the true body
      const std::size_t e = nearest_element(points[at]);
      const double nearest[kStressSlots] = {fem.sigma_x[e], fem.sigma_y[e], fem.sigma_z[e], fem.tau_xy[e],
                                            fem.tau_yz[e],  fem.tau_xz[e],  fem.von_mises[e]};  // the element's own
      std::copy(nearest, nearest + kStressSlots, s);
      ++outside[0];
    }
    at += gauss;
  }
  for (std::size_t node : body_node_ids(grid)) {  // the order of agent_probe_points
    const auto& probe = fem.probes[at];
    const auto u = probe.found ? probe.u : fem.displacement_at(points[at]);
    outside[1] += !probe.found;
    for (int a = 0; a < dim; ++a) out.u[node * dim + a] = u[a];
    ++at;
  }
  return out;
}

namespace {

/// The stress record of the source agent holding `p` (`slot` set to it), or its agent neighbours'
/// bilinear value in air (`slot` npos); false outside their reach.
bool source_stress(const agent::Grid& source, const GridFields& fields, const std::array<double, 3>& p,
                   std::size_t& slot, double s[kStressSlots]) {
  int c[3];
  slot = locate_cell(source, p.data(), c) ? source.index(c[0], c[1], c[2]) : agent::Grid::npos;
  if (slot != agent::Grid::npos && !source.is_air(slot)) {
    std::copy_n(&fields.stress[kStressSlots * slot], kStressSlots, s);
    return true;
  }
  slot = agent::Grid::npos;
  const Eigen::Vector3d x(p[0], p[1], p[2]);
  for (int k = 0; k < kStressSlots; ++k) s[k] = sample_cells(source, fields.stress, kStressSlots, k, x);
  return std::isfinite(s[0]);
}

}  // namespace

GridFields agents_on_grid(const agent::Grid& grid, const agent::Grid& source, const GridFields& fields,
                          const std::string& what) {
  if (grid.dim == source.dim && grid.cells == source.cells && grid.origin == source.origin &&
      grid.size == source.size && grid.flags == source.flags && grid.planes == source.planes)
    return fields;  // the same grid: its own values, bit for bit
  const auto points = agent_probe_points(grid);
  const int dim = grid.dim, gauss = 1 << dim;
  auto outside = [&](const std::array<double, 3>& p) {
    return Error(what + ": the point (" + std::to_string(p[0]) + ", " + std::to_string(p[1]) + ", " +
                 std::to_string(p[2]) + ") m of the body lies beyond its agents");
  };
  GridFields out;
  out.stress.assign(grid.count() * kStressSlots, 0.0);
  out.u.assign(grid.node_count() * dim, 0.0);
  std::size_t at = 0;
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    if (grid.is_air(cell)) continue;
    double* s = &out.stress[kStressSlots * cell];
    double q[kStressSlots];
    std::size_t first = agent::Grid::npos, slot = 0;
    bool one_agent = true;
    for (int g = 0; g < gauss; ++g, ++at) {
      if (!source_stress(source, fields, points[at], slot, q)) throw outside(points[at]);
      one_agent = one_agent && slot != agent::Grid::npos && (g == 0 || slot == first);
      if (g == 0) first = slot;
      for (int k = 0; k < kStressSlots; ++k) s[k] += q[k];
    }
    if (one_agent) {
      std::copy_n(&fields.stress[kStressSlots * first], kStressSlots, s);
    } else {
      for (int k = 0; k < 6; ++k) s[k] /= gauss;
      s[kVonMises] = von_mises(s);
    }
  }
  for (std::size_t node : body_node_ids(grid)) {  // the order of agent_probe_points
    const Eigen::Vector3d x(points[at][0], points[at][1], points[at][2]);
    for (int a = 0; a < dim; ++a) {
      out.u[node * dim + a] = sample_nodes(source, fields.u, dim, a, x);
      if (!std::isfinite(out.u[node * dim + a])) throw outside(points[at]);
    }
    ++at;
  }
  return out;
}

}  // namespace compare
