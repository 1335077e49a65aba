// The FEM reference on the agent grid: solving it at two refinement levels and sampling FEM
// results onto the agents by point location.
#include <compare/reference.h>

#include "report.h"

#include <agent_study.h>
#include <workbench/error.h>

#include <chrono>
#include <cmath>
#include <ostream>

namespace compare {

using workbench::Error;

namespace {

/// Grid index along each axis of the cell holding `p` (-1 when outside the grid's box).
bool locate_cell(const agent::Grid& g, const double* p, int idx[3]) {
  idx[0] = idx[1] = idx[2] = 0;
  for (int a = 0; a < g.dim; ++a) {
    const double f = (p[a] - g.origin[a]) / g.size[a];
    idx[a] = int(std::floor(f));
    if (idx[a] < 0 || idx[a] >= g.cells[a]) return false;
  }
  return true;
}

/// Grid node at `p` (within 1e-6 agent sizes), if there is one.
bool locate_node(const agent::Grid& g, const double* p, int idx[3]) {
  idx[0] = idx[1] = idx[2] = 0;
  for (int a = 0; a < g.dim; ++a) {
    const double f = (p[a] - g.origin[a]) / g.size[a];
    idx[a] = int(std::lround(f));
    if (std::abs(f - idx[a]) > 1e-6 || idx[a] < 0 || idx[a] > g.cells[a]) return false;
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
  out.sigma.assign(grid.count() * 2, 0.0);
  std::vector<int> hits(grid.count(), 0);
  for (std::size_t e = 0; e < fem.cell_count(); ++e) {
    int c[3];
    if (!locate_cell(grid, &fem.cell_centres[3 * e], c)) continue;
    const std::size_t cell = grid.index(c[0], c[1], c[2]);
    out.sigma[2 * cell] += fem.sigma_x[e];
    out.sigma[2 * cell + 1] += fem.sigma_y[e];
    ++hits[cell];
  }
  for (std::size_t cell : mesh.cell_of_element) {
    if (hits[cell] == 0)
      throw Error(case_name + ": no FEM cell centre lies in agent " + std::to_string(cell) +
                  " (the FEM mesh does not cover the agents' body, or its cells are larger than the agents)");
    out.sigma[2 * cell] /= hits[cell];
    out.sigma[2 * cell + 1] /= hits[cell];
  }
  out.u.assign(grid.node_count() * dim, 0.0);
  std::vector<char> found(grid.node_count(), 0);
  for (std::size_t n = 0; n < fem.node_count(); ++n) {
    int p[3];
    if (!locate_node(grid, &fem.node_points[3 * n], p)) continue;
    const std::size_t node = grid.node_index(p[0], p[1], p[2]);
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

GridFields agent_on_grid(const agent::Grid& grid, const agent_study::AgentState& state) {
  GridFields out;
  out.sigma.resize(grid.count() * 2);
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    out.sigma[2 * cell] = state.stress[cell * grid.dim];
    out.sigma[2 * cell + 1] = state.stress[cell * grid.dim + 1];
  }
  out.u = state.displacement;
  return out;
}

std::string ReferenceOptions::describe() const {
  return "FEM Q" + std::to_string(degree) + (refine == 0 ? std::string(" on the agents' mesh")
                                                          : ", the agents' mesh refined " + std::to_string(refine) +
                                                                (refine == 1 ? " time" : " times"));
}

Reference solve_reference(fem_reference::FemProblem problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log) {
  Reference r;
  const std::string name = problem.name;
  problem.options.degree = options.degree;
  problem.options.refine = options.refine;
  log << "compare: reference " << options.describe() << "\n";
  r.fem = report::run_fem(problem, dir, log, r.seconds);
  r.fields = fem_on_grid(mesh, r.fem, name);

  const auto start = std::chrono::steady_clock::now();
  r.estimate = options.estimate();
  problem.options.degree = r.estimate.degree;
  problem.options.refine = r.estimate.refine;
  problem.options.write_vtu = false;
  log << "compare: the reference's error estimate: against " << r.estimate.describe() << "\n";
  const auto estimate = fem_reference::solve_fem(problem, {}, &log);
  r.estimate_fields = fem_on_grid(mesh, estimate, name);
  r.estimate_dofs = estimate.n_dofs;
  r.estimate_seconds = report::seconds_since(start);
  return r;
}

}  // namespace compare
