// The PBD model's cost-accuracy front (docs/front.md, "A PBD case"), in steps: read and check the
// case (the rod and the strip one body under one load), solve the case's FEM strip (the reference)
// and the strip of half its cells (the reference's own error), run the PBD ladder (substeps x
// iterations) and the FEM strip's ladder (cells x degree), judge, write.
#include "front_files.h"
#include "front_ladder.h"
#include "pbd_strip.h"
#include "report.h"

#include <compare/metrics.h>
#include <fem_reference/fem.h>
#include <workbench/case_edit.h>
#include <workbench/error.h>

#include <chrono>
#include <cmath>
#include <set>
#include <sstream>

namespace compare {

namespace fs = std::filesystem;
using workbench::Error;

namespace {

/// The metrics of the PBD front: those of `workbench compare` (model = "pbd") against the FEM.
const std::vector<std::string> kPbdMetrics = {"centreline.deflection.rel_l2", "tip.deflection.rel_error"};

/// What every point of the PBD front is scored against.
struct PbdFrontContext {
  const schema::FrontOptions& options;
  const pbd_study::PbdStudy& study;
  const Rod& rod;
  const fem_reference::FemProblem& problem;  ///< the case's FEM strip
  double D = 0;                              ///< the strip's height [m]
  double cells = 0;                          ///< the case's value of front.cells_parameter
  std::vector<double> reference_uy;          ///< the reference's u_y at the rod's nodes (s >= 0)
};

/// The rod's nodes at s >= 0 (the ghost node inside the clamp left out), in order from the clamp.
std::vector<int> rod_nodes(const Rod& rod) {
  std::vector<int> out;
  for (std::size_t k = 0; k < rod.line.nodes.size(); ++k)
    if (rod.line.s[k] >= -1e-12 * rod.L) out.push_back(rod.line.nodes[k]);
  return out;
}

/// A FEM strip's u_y at the rod's rest nodes.
std::vector<double> fem_deflection(const PbdFrontContext& c, const fem_reference::FemResult& fem) {
  const RowSampler sampler(fem, 1e-6 * c.D);
  std::vector<double> uy;
  for (int node : rod_nodes(c.rod)) {
    const auto& p0 = c.study.mesh.mesh.points[node];
    uy.push_back(sampler.at(p0[0], p0[1])[1]);
  }
  return uy;
}

/// kPbdMetrics of a deflection `uy` against `reference`.
std::map<std::string, double> errors(const std::vector<double>& uy, const std::vector<double>& reference) {
  return {{kPbdMetrics[0], relative_errors(uy, reference).rel_l2},
          {kPbdMetrics[1], std::abs(uy.back() - reference.back()) / std::abs(reference.back())}};
}

/// The case's study with `substeps` x `iterations` per frame, at rest (its frames not yet run).
pbd_study::PbdStudy with_steps(const pbd_study::PbdStudy& study, int substeps, int iterations) {
  pbd_study::PbdStudy s = study;
  s.setup.step.substeps = substeps;
  s.setup.step.iterations = iterations;
  return s;
}

/// Runs the case's frames (a workbench::Error when the rod diverges).
void relax(pbd_study::PbdStudy& s) {
  pbd::Solver solver(s.model);
  std::ostringstream quiet;  // the frames' progress: the front logs each point instead
  pbd_study::step_frames(s, solver, [](int) {}, quiet);
}

std::string pbd_label(int substeps, int iterations) {
  return "pbd " + std::to_string(substeps) + " x " + std::to_string(iterations);
}

FrontPoint pbd_point(const PbdFrontContext& c, int substeps, int iterations) {
  FrontPoint p;
  p.model = "pbd";
  p.label = pbd_label(substeps, iterations);
  const auto nodes = rod_nodes(c.rod);
  p.size = c.rod.L / double(nodes.size() - 1);
  auto warm = with_steps(c.study, substeps, iterations);
  relax(warm);  // the warm-up: its deflection is scored
  time_runs(c.options.runs, p, [&] {
    const auto t0 = std::chrono::steady_clock::now();
    auto s = with_steps(c.study, substeps, iterations);
    const double copy_seconds = report::seconds_since(t0);
    relax(s);
    return copy_seconds;
  });
  std::vector<double> uy;
  for (int node : nodes) uy.push_back(warm.model.particles.x[node][1] - c.study.mesh.mesh.points[node][1]);
  const auto& model = c.study.model;
  const double frames = c.study.setup.frames;
  p.work = {{"nodes", double(model.particles.size())}, {"frames", frames}, {"substeps", double(substeps)},
            {"iterations_per_substep", double(iterations)},
            {"projections", frames * substeps * iterations * double(model.angles.size() + model.distances.size())}};
  p.errors = errors(uy, c.reference_uy);
  return p;
}

/// The case's FEM strip with `cells` cells along it (front.cells_parameter), of `degree`, solved
/// by the project's fastest path for its size.
fem_reference::FemProblem strip_problem(const PbdFrontContext& c, double cells, int degree) {
  auto problem = c.problem;
  problem.mesh_parameters[c.options.cells_parameter] = cells;
  problem.options.degree = degree;
  problem.options.solver = fem_reference::SolverKind::Auto;
  problem.options.refine = 0;
  problem.options.write_vtu = false;
  problem.options.coarser_level = false;
  return problem;
}

FrontPoint fem_point(const PbdFrontContext& c, double factor, int degree) {
  FrontPoint p;
  p.model = "fem";
  p.degree = degree;
  const double cells = std::max(1.0, std::round(c.cells / factor));
  p.size = c.rod.L / cells;
  p.label = "fem Q" + std::to_string(degree) + " " + std::to_string(long(cells)) + " cells";
  const auto problem = strip_problem(c, cells, degree);
  const auto warm = fem_reference::solve_fem(problem);
  time_runs(c.options.runs, p, [&] { return fem_reference::solve_fem(problem).mesh_seconds; });
  p.work = {{"mesh_seconds", warm.mesh_seconds}, {"dofs", double(warm.n_dofs)}, {"cells", double(warm.n_active_cells)},
            {"iterations", double(warm.iterations)}};
  p.errors = errors(fem_deflection(c, warm), c.reference_uy);
  return p;
}

/// [front] pbd_substeps, or the case's substeps times 1/8 .. 2.
std::vector<int> substeps_ladder(const schema::FrontOptions& o, int own) {
  if (!o.pbd_substeps.empty()) return o.pbd_substeps;
  std::set<int> out;
  for (double f : {0.125, 0.25, 0.5, 1.0, 2.0}) out.insert(std::max(1, int(std::lround(f * own))));
  return {out.begin(), out.end()};
}

/// [front] pbd_iterations, or 1, 2, 4, 8 and the case's own.
std::vector<int> iterations_ladder(const schema::FrontOptions& o, int own) {
  if (!o.pbd_iterations.empty()) return o.pbd_iterations;
  std::set<int> out{1, 2, 4, 8, own};
  return {out.begin(), out.end()};
}

void run_ladders(const PbdFrontContext& c, FrontOutcome& out, std::ostream& log) {
  const auto& step = c.study.setup.step;
  for (int iterations : iterations_ladder(c.options, step.iterations))
    for (int substeps : substeps_ladder(c.options, step.substeps))
      add_point(out, log, pbd_label(substeps, iterations), kPbdMetrics[0],
                [&] { return pbd_point(c, substeps, iterations); });
  for (int degree : c.options.fem_degrees)
    for (double f : c.options.fem_sizes)
      add_point(out, log, "fem Q" + std::to_string(degree) + " at " + std::to_string(std::lround(c.cells / f)) + " cells",
                kPbdMetrics[0], [&] { return fem_point(c, f, degree); });
}

/// Two models under different loads or stiffnesses are an error, not a bad score.
void require_same_strip(const Strip& st, const std::string& case_name) {
  auto off = [](double a, double b) { return !(std::abs(a / b - 1) <= 1e-3); };
  std::ostringstream why;
  why.precision(6);
  if (off(st.W_pbd, st.W_fem))
    why << "pbd.total_mass, pbd.gravity, pbd.node_force: the PBD rod carries " << st.W_pbd << " N, the FEM strip "
        << st.W_fem << " N (fem.body_force, [[load]])";
  else if (off(st.EI_pbd, st.EI))
    why << "pbd.young, pbd.second_moment: the PBD rod's E I is " << st.EI_pbd << " N m^2, the FEM strip's "
        << st.EI << " N m^2 (material.young, material.thickness, its height)";
  if (!why.str().empty())
    throw Error(case_name + ": " + why.str() + ": the front compares one strip under one load (nothing was run)");
}

/// The case's value of front.cells_parameter, or a case-file error naming the key.
double case_cells(const workbench::CaseFile& file, const fem_reference::FemProblem& problem,
                  const std::string& parameter) {
  const auto it = problem.mesh_parameters.find(parameter);
  if (it == problem.mesh_parameters.end())
    file.root().table("front").fail("cells_parameter", "the FEM strip's mesh has no parameter \"" + parameter +
                                                           "\" ([mesh.parameters]) counting its cells along the strip");
  return it->second;
}

/// What the PBD front reads and checks before it runs anything: one strip, one load.
struct PbdFrontInput {
  fem_reference::FemProblem problem;
  pbd_study::PbdStudy study;
  Rod rod;
  double D = 0, cells = 0;
};

PbdFrontInput read_pbd_front(const workbench::CaseFile& file, const schema::FrontOptions& options) {
  const std::string case_name = file.path().string();
  auto problem = fem_reference::problem_from_case(file);
  const double cells = case_cells(file, problem, options.cells_parameter);
  front_files::check_gate_names(options.gate, kPbdMetrics, file);
  file.reject_unknown_keys();
  auto study = pbd_study::load_pbd_study(file, pbd_study::read_pbd_case(file));
  const Rod rod = check_rod(study, file.root().table("pbd"));
  const double D = strip_height(strip_extent(problem), rod, case_name);
  require_same_strip(strip(problem, study, rod, D), case_name);
  return {std::move(problem), std::move(study), rod, D, cells};
}

}  // namespace

void check_pbd_front(const workbench::CaseFile& file, const schema::FrontOptions& options) {
  read_pbd_front(file, options);
}

FrontOutcome run_pbd_front(const workbench::CaseFile& file, const schema::FrontOptions& options, const fs::path& dir,
                           std::ostream& log) {
  // 1. Read and check everything before running anything.
  const std::string case_name = file.path().string();
  const auto input = read_pbd_front(file, options);
  const auto& [problem, study, rod, D, cells] = input;
  // 2. The reference (the case's strip, its files in dir/fem) and its own error: the strip of half its cells.
  double reference_seconds = 0;
  const auto reference = report::run_fem(problem, dir, log, reference_seconds);
  if (reference.dim != 2) throw Error(case_name + ": model = \"pbd\" compares with a 2D FEM strip, got a 3D mesh");
  PbdFrontContext c{options, study, rod, problem, D, cells, {}};
  c.reference_uy = fem_deflection(c, reference);
  const auto estimate = fem_reference::solve_fem(strip_problem(c, std::round(cells / 2), reference.degree));
  FrontOutcome out;
  out.reference_errors = errors(fem_deflection(c, estimate), c.reference_uy);
  // 3. The ladders.
  run_ladders(c, out, log);
  out.case_point = pbd_label(study.setup.step.substeps, study.setup.step.iterations);
  if (std::none_of(out.points.begin(), out.points.end(), [&](const FrontPoint& p) { return p.label == out.case_point; }))
    throw Error(case_name + ": front.pbd_substeps, front.pbd_iterations: the case's own " + out.case_point +
                " did not run (" + (out.skipped.empty() ? std::string("not in the ladder") : out.skipped.front()) + ")");
  // 4. The verdicts, the gate, the files.
  out.verdicts = front_verdicts(out.points, kPbdMetrics, out.reference_errors);
  out.crossovers = front_crossovers(out.points, kPbdMetrics, out.reference_errors);
  front_files::apply_gate(options.gate, out);
  const std::string p = options.cells_parameter;
  const front_files::FrontHeader header{
      study.setup.title, kPbdMetrics, kPbdMetrics,
      {{"description", "the case's FEM strip, Q" + std::to_string(reference.degree) + ", " + p + " = " +
                           workbench::toml_number(cells)},
       {"dofs", reference.n_dofs},
       {"estimate", "the same strip with " + p + " = " + workbench::toml_number(std::round(cells / 2))},
       {"estimate_dofs", estimate.n_dofs}}};
  front_files::write(dir, file, header, options, out, log);
  return out;
}

}  // namespace compare
