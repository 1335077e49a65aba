// The FEM reference on the agent grid: solving it at two refinement levels, sampled onto the agents.
#include <compare/reference.h>

#include "report.h"

#include <agent_study.h>
#include <compare/metrics.h>
#include <fem_reference/mpi.h>
#include <workbench/error.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <ostream>
#include <sstream>

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

OwnError body_own_error(const agent::ImportedMesh& mesh, const GridFields& reference, const GridFields& estimate) {
  const auto& grid = mesh.grid;
  std::vector<char> body(grid.count(), 0);
  for (std::size_t cell : mesh.cell_of_element) body[cell] = 1;
  const auto ids = agent_ids(grid);  // box order, as the summary's body scope sums
  OwnError out;
  double largest = -1;
  for (const auto& field : kFields) {
    if (field.per_node || field.slot == kVonMises || !field.in(grid.dim)) continue;
    std::vector<double> ref, est;
    for (std::size_t id : ids)
      if (body[id]) {
        ref.push_back(reference.stress[kStressSlots * id + field.slot]);
        est.push_back(estimate.stress[kStressSlots * id + field.slot]);
      }
    double norm = 0;
    for (double v : ref) norm += v * v;
    if (norm > largest) out = {field.name, relative_errors(est, ref).rel_l2}, largest = norm;
  }
  return out;
}

namespace {

std::string number(double v) {
  std::ostringstream s;
  s << std::setprecision(3) << v;
  return s.str();
}

/// One level of the reference (solve_reference without `converges`).
Reference solve_level(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                      const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log) {
  Reference r;
  r.options = options;
  r.estimate = options.estimate();
  log << "compare: reference " << options.describe() << "\n";
  auto reference = reference_problem(problem, options, mesh.grid);
  // The estimate level is the multigrid's coarse mesh when the reference is refined once: solved
  // from that hierarchy first, and the reference's CG starts from it (FemOptions::coarser_level).
  if (options.refine == 1 && r.estimate.degree == options.degree && r.estimate.refine == 0) {
    reference.options.coarser_level = true;
    reference.options.coarser_share = options.algebraic_share;
  }
  if (dir.empty()) {  // no files (the calibration's references)
    const auto start = std::chrono::steady_clock::now();
    r.fem = fem_reference::solve_fem(reference, {}, &log);
    r.seconds = report::seconds_since(start);
  } else {
    r.fem = report::run_fem(reference, dir, log, r.seconds);
  }
  r.fields = reference_on_grid(options, mesh, r.fem, problem.name, r.outside);
  return r;
}

/// The estimate level of `r` on the agent grid: from the reference's multigrid hierarchy when it
/// has it, else solved without output.
void solve_estimate(Reference& r, const fem_reference::FemProblem& problem, const agent::ImportedMesh& mesh,
                    std::ostream& log) {
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
  r.estimated = true;
}

/// Rank 0's own error of `r`, on every rank (the ranks' fields are the same: the decision is one).
OwnError agreed_own_error(const Reference& r, const agent::ImportedMesh& mesh) {
  OwnError e = body_own_error(mesh, r.fields, r.estimate_fields);
  std::size_t index = 0;
  while (index < std::size(kFields) && kFields[index].name != e.field) ++index;
  std::vector<double> agreed{fem_reference::mpi_rank() == 0 ? e.rel_l2 : 0.0,
                             fem_reference::mpi_rank() == 0 ? double(index) : 0.0};
  fem_reference::mpi_sum(agreed);
  return {kFields[std::size_t(agreed[1])].name, agreed[0]};
}

/// The converging default: levels from options.refine on, each with its estimate (the level before
/// it when that is its estimate level, from the multigrid at refine 1), until the own error is at
/// most the tolerance or the next level cannot be taken (the memory estimate, kMaxRefine).
Reference converge(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                   const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log) {
  log << "compare: reference: the 3D default, refined until its own error in the body is at most "
      << options.tolerance << " ([compare.reference] tolerance)\n";
  std::vector<Reference::Level> levels;
  GridFields previous;  // the level before on the agent grid (its solve's result freed)
  for (int level = options.refine;; ++level) {
    const auto start = std::chrono::steady_clock::now();
    Reference r = solve_level(problem, options.at(level), mesh, dir, log);
    if (!levels.empty() && !r.fem.coarser && options.at(level - 1).describe() == r.estimate.describe()) {
      r.estimate_fields = std::move(previous);  // the level before is this one's estimate
      r.estimate_dofs = levels.back().dofs;
      r.estimated = true;
    } else {
      solve_estimate(r, problem, mesh, log);
    }
    levels.push_back({level, r.fem.n_dofs, agreed_own_error(r, mesh), report::seconds_since(start)});
    const auto& e = levels.back().error;
    std::string stopped;
    if (e.rel_l2 > options.tolerance) {
      const auto next = options.at(level + 1);
      stopped = level >= ReferenceOptions::kMaxRefine
                    ? "it has the most refinements a reference takes (" + std::to_string(level) + ")"
                    : fem_reference::fem_memory_refusal(reference_problem(problem, next, mesh.grid));
      if (!stopped.empty() && level < ReferenceOptions::kMaxRefine)
        stopped = "the next level (" + next.describe() + ") would not fit: " + stopped;
    }
    log << "compare: reference level " << level << " (" << r.options.describe() << ", " << r.fem.n_dofs << " DoFs, "
        << number(levels.back().seconds) << " s): its own error in the body's " << e.field << " " << number(e.rel_l2)
        << (e.rel_l2 <= options.tolerance ? " <= " : " > ") << options.tolerance
        << (e.rel_l2 <= options.tolerance ? ": converged" : stopped.empty() ? ": refining once more" : ": stopping")
        << "\n";
    if (e.rel_l2 <= options.tolerance || !stopped.empty()) {
      r.levels = std::move(levels);
      r.stopped = std::move(stopped);
      if (!r.stopped.empty()) log << "compare: warning: " << r.limits_judgement() << "\n";
      return r;
    }
    previous = std::move(r.fields);
  }
}

}  // namespace

std::string Reference::limits_judgement() const {
  if (stopped.empty() || levels.empty()) return {};
  const auto& e = levels.back().error;
  return "the reference limits the judgement: its own error in the body's " + e.field + " is " + number(e.rel_l2) +
         " (" + options.describe() + " against " + estimate.describe() + "), above the tolerance " +
         number(options.tolerance) + " ([compare.reference] tolerance); it was not refined further: " + stopped;
}

Reference solve_reference(const fem_reference::FemProblem& problem, const ReferenceOptions& options,
                          const agent::ImportedMesh& mesh, const std::filesystem::path& dir, std::ostream& log) {
  return options.converges ? converge(problem, options, mesh, dir, log) : solve_level(problem, options, mesh, dir, log);
}

void estimate_reference_error(Reference& r, fem_reference::FemProblem problem, const agent::ImportedMesh& mesh,
                              std::ostream& log, const std::filesystem::path& staircase_msh) {
  if (!r.estimated) solve_estimate(r, problem, mesh, log);
  const auto& options = r.options;
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

nlohmann::json level_json(const Reference& r) {
  nlohmann::json json{{"description", r.options.describe()},
                      {"degree", r.options.degree},
                      {"refine", r.options.refine},
                      {"dofs", r.fem.n_dofs}};
  if (!r.levels.empty()) json["convergence"] = convergence_json(r);  // the 3D default
  return json;
}

nlohmann::json convergence_json(const Reference& r) {
  auto levels = nlohmann::json::array();
  for (const auto& l : r.levels)
    levels.push_back({{"refine", l.refine}, {"dofs", l.dofs}, {"own_error", l.error.rel_l2}, {"seconds", l.seconds}});
  const auto& last = r.levels.back().error;
  nlohmann::json json{{"tolerance", r.options.tolerance}, {"scope", "body"}, {"field", last.field},
                      {"own_error", last.rel_l2}, {"converged", r.stopped.empty()},
                      {"limits_judgement", !r.stopped.empty()}, {"levels", levels},
                      {"rule", "refined from Q2 on the agents' mesh until the relative L2 error of its estimate level "
                               "against it, over the body, in its largest stress component (the body rel_l2 "
                               "reference_error of that field), is at most the tolerance, while the next level's "
                               "memory estimate fits"}};
  if (!r.stopped.empty()) json["stopped"] = r.stopped;
  return json;
}

}  // namespace compare
