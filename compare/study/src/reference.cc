// The FEM reference on the agent grid: solving it at two refinement levels, sampled onto the agents.
#include <compare/reference.h>

#include "report.h"

#include <agent_study.h>
#include <compare/metrics.h>
#include <workbench/error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ostream>

namespace compare {

using workbench::Error;

GridFields agent_on_grid(const agent::Grid& grid, const agent::AgentState& state) {
  GridFields out;
  out.stress.assign(grid.count() * kStressSlots, 0.0);
  for (std::size_t cell = 0; cell < grid.count(); ++cell) {
    double* s = &out.stress[kStressSlots * cell];
    std::copy(state.stress[cell].begin(), state.stress[cell].end(), s);  // the slots' order
    s[kVonMises] = von_mises(s);  // the general form (the agents' own 2D outputs: plane stress's)
  }
  out.u = state.displacement;
  return out;
}

ReferenceOptions reference_options(const CompareOptions& options, const agent_study::AgentStudy& study) {
  auto reference = options.reference.resolved(study.mesh.grid.dim);
  if (reference.mesh.empty() && study.setup.agent_size > 0) reference.mesh = study.setup.mesh_file;
  return reference;
}

fem_reference::FemProblem reference_problem(fem_reference::FemProblem problem, const ReferenceOptions& options,
                                            const agent::Grid& grid) {
  problem.options.degree = options.degree;
  problem.options.refine = options.refine;
  if (!options.mesh.empty()) {  // the same body, loads and supports on the true geometry's mesh, evaluated at the agents
    if (options.mesh != problem.mesh_file) problem.mesh_parameters.clear();  // another file's
    problem.mesh_file = options.mesh;
    problem.box.reset();
    problem.probe_points = agent_probe_points(grid);
  }
  return problem;
}

GridFields reference_on_grid(const ReferenceOptions& options, const agent::ImportedMesh& mesh,
                             const fem_reference::FemResult& fem, const std::string& case_name,
                             std::array<std::size_t, 2>& outside) {
  return options.mesh.empty() ? fem_on_grid(mesh, fem, case_name) : fem_at_agents(mesh.grid, fem, outside);
}

Reference solve_reference(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log) {
  Reference r;
  r.estimate = options.estimate();
  log << "compare: reference " << options.describe() << "\n";
  auto reference = reference_problem(problem, options, mesh.grid);
  // The estimate level is the multigrid's coarse mesh when the reference is refined once: solved
  // from that hierarchy first, and the reference's CG starts from it (FemOptions::coarser_level).
  if (options.refine == 1 && r.estimate.degree == options.degree && r.estimate.refine == 0) {
    reference.options.coarser_level = true;
    reference.options.coarser_share = options.algebraic_share;
  }
  r.fem = report::run_fem(reference, dir, log, r.seconds);
  r.fields = reference_on_grid(options, mesh, r.fem, problem.name, r.outside);
  return r;
}

void estimate_reference_error(Reference& r, fem_reference::FemProblem problem, const ReferenceOptions& options,
                              const agent::ImportedMesh& mesh, std::ostream& log, const std::filesystem::path& staircase_msh) {
  const auto start = std::chrono::steady_clock::now();
  if (r.fem.coarser) {  // solved with the reference, from its multigrid hierarchy
    log << "compare: the reference's error estimate: against " << r.estimate.describe()
        << " (the coarse level of the reference's multigrid)\n";
    r.estimate_fields = reference_on_grid(r.estimate, mesh, *r.fem.coarser, problem.name, r.outside);
    r.estimate_dofs = r.fem.coarser->n_dofs;
  } else {
    fem_reference::FemProblem estimate_problem = reference_problem(problem, r.estimate, mesh.grid);
    estimate_problem.options.write_vtu = false;
    log << "compare: the reference's error estimate: against " << r.estimate.describe() << "\n";
    const auto estimate = fem_reference::solve_fem(estimate_problem, {}, &log);
    r.estimate_fields = reference_on_grid(r.estimate, mesh, estimate, problem.name, r.outside);
    r.estimate_dofs = estimate.n_dofs;
  }
  r.estimate_seconds = report::seconds_since(start);

  if (!options.mesh.empty()) {  // the true geometry: FEM on the staircase at the reference's level
    problem.options.degree = options.degree;
    problem.options.refine = options.refine;
    problem.options.write_vtu = false;
    if (!staircase_msh.empty()) {  // written in metres
      problem.mesh_file = staircase_msh;
      problem.mesh_parameters.clear();
      problem.mesh_unit = 1.0;
    }
    log << "compare: the staircase's own error: FEM on the agents' mesh at the reference's level\n";
    const auto staircase = fem_reference::solve_fem(problem, {}, &log);
    r.staircase_fields = fem_on_grid(mesh, staircase, problem.name);
    r.staircase_dofs = staircase.n_dofs;
  }
}

}  // namespace compare
