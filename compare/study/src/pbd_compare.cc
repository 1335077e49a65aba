// The PBD angle bending rod against the deal.II FEM strip (docs/compare.md "model = pbd"):
// PBD relaxed to rest from the case's frames, FEM solved once, the FEM displacement sampled on the
// strip's mid-height line at the PBD centreline's nodes, both against Euler-Bernoulli.
#include <compare/pbd_compare.h>
#include <compare/metrics.h>

#include "pbd_strip.h"
#include "report.h"

#include <fem_reference/fem_case.h>
#include <pbd_study.h>
#include <workbench/csv_file.h>
#include <workbench/error.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <ostream>
#include <sstream>
#include <utility>

namespace compare {

namespace fs = std::filesystem;
using workbench::open_csv;
using report::seconds_since;
using workbench::Error;

namespace {

/// Every metric of the PBD comparison, with its meaning: the one list metric_names and the
/// summary use, so that a gate can name exactly what is computed.
const std::pair<const char*, const char*> kMetrics[] = {
    {"centreline.deflection.rel_l2", "||u_y PBD - u_y FEM||_2 / ||u_y FEM||_2 over the centreline nodes (s >= 0)"},
    {"centreline.deflection.rel_max", "max |u_y PBD - u_y FEM| / max |u_y FEM| over the centreline nodes"},
    {"tip.deflection.rel_error", "|u_y PBD - u_y FEM| / |u_y FEM| at the free end (s = L)"},
    {"pbd.tip.euler_bernoulli.rel_error", "|u_y PBD - u_y EB| / |u_y EB| at the free end"},
    {"fem.tip.euler_bernoulli.rel_error", "|u_y FEM - u_y EB| / |u_y EB| at the free end"},
    {"pbd.centreline.euler_bernoulli.rel_l2", "||u_y PBD - u_y EB||_2 / ||u_y EB||_2 over the centreline nodes"},
    {"fem.centreline.euler_bernoulli.rel_l2", "||u_y FEM - u_y EB||_2 / ||u_y EB||_2 over the centreline nodes"},
    {"pbd.bending_stiffness_dev", "|E I of [pbd] / E I of the FEM strip (E t D^3 / 12) - 1|"},
    {"pbd.load_dev", "|transverse load of [pbd] / that of the FEM strip (body force and [[load]]) - 1|"},
    {"pbd.steady.max_speed", "largest node speed after the last frame [m/s]"},
    {"pbd.steady.rel_change", "max speed * time_step / max displacement: relative motion in one more frame"},
    {"pbd.steady.kinetic_energy", "kinetic energy after the last frame [J]"},
    {"pbd.steady.max_stretch", "largest relative stretch |l - l0| / l0 of a distance constraint"},
    {"fem.equilibrium_dev", "|reactions + applied| / |applied| (FEM)"},
    {"time.pbd_s", "PBD frames with output [s]"},
    {"time.fem_s", "FEM reference with output [s]"},
    {"time.compare_s", "comparison and its output [s]"},
    {"time.figures_s", "figure [s]"},
    {"time.total_s", "the whole study [s]"},
};

}  // namespace

std::vector<std::string> pbd_metric_names() {
  std::vector<std::string> names;
  for (const auto& [name, meaning] : kMetrics) names.push_back(name);
  return names;
}

namespace {

/// How still the rod is after its frames.
struct Steady {
  double max_speed = 0, max_u = 0, max_stretch = 0;
};

Steady steady_state(pbd_study::PbdStudy& study) {
  const auto& particles = study.model.particles;
  Steady s;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.w[i] > 0) s.max_speed = std::max(s.max_speed, particles.v[i].norm());
    s.max_u = std::max(s.max_u, (particles.x[i] - study.mesh.mesh.points[i]).norm());
  }
  s.max_stretch = pbd::Solver(study.model).residuals().distance;
  return s;
}

/// Both models along the centreline (s >= 0; the ghost node inside the clamp is left out).
struct Samples {
  std::vector<double> s, pbd_uy, fem_uy, eb_uy, rest, pbd_u, fem_u;  // rest, pbd_u, fem_u: (x, y) per node
};

/// Samples along the centreline and writes centreline.csv into `dir`.
Samples sample_centreline(const pbd_study::PbdStudy& study, const Rod& rod, const Strip& st,
                          const fem_reference::FemResult& fem, const std::string& case_name, const fs::path& dir) {
  const auto& mesh = study.mesh.mesh;
  const auto& particles = study.model.particles;
  const auto& line = rod.line;
  const RowSampler sampler(fem, 1e-6 * st.D);
  Samples out;
  auto csv = open_csv(dir / "centreline.csv");
  csv << "s [m],x0 [m],y0 [m],pbd_x [m],pbd_y [m],pbd_u_x [m],pbd_u_y [m],fem_u_x [m],fem_u_y [m],eb_u_y [m]\n";
  for (std::size_t k = 0; k < line.nodes.size(); ++k) {
    if (line.s[k] < -1e-12 * rod.L) continue;
    const int node = line.nodes[k];
    const pbd::Vec3 &p0 = mesh.points[node], &p = particles.x[node];
    std::array<double, 2> uf;
    try {
      uf = sampler.at(p0[0], p0[1]);
    } catch (const Error& e) {
      throw Error(case_name + ": sampling the FEM strip at s = " + std::to_string(line.s[k]) + ": " + e.what());
    }
    out.s.push_back(line.s[k]);
    out.pbd_uy.push_back(p[1] - p0[1]);
    out.fem_uy.push_back(uf[1]);
    out.eb_uy.push_back(st.eb(line.s[k]));
    out.rest.insert(out.rest.end(), {p0[0], p0[1]});
    out.pbd_u.insert(out.pbd_u.end(), {p[0] - p0[0], p[1] - p0[1]});
    out.fem_u.insert(out.fem_u.end(), {uf[0], uf[1]});
    csv << line.s[k] << ',' << p0[0] << ',' << p0[1] << ',' << p[0] << ',' << p[1] << ',' << p[0] - p0[0] << ','
        << p[1] - p0[1] << ',' << uf[0] << ',' << uf[1] << ',' << out.eb_uy.back() << '\n';
  }
  csv.close();
  return out;
}

/// centreline.csv's columns, in memory.
FieldTable centreline_table(Samples samples) {
  FieldTable centreline;
  centreline.add("arc_length", 1, samples.s), centreline.add("point", 2, std::move(samples.rest));
  centreline.add("pbd_u", 2, std::move(samples.pbd_u)), centreline.add("fem_u", 2, std::move(samples.fem_u));
  centreline.add("eb_u_y", 1, samples.eb_uy);
  return centreline;
}

/// A metric of kMetrics, with its meaning.
void add_metric(const std::string& name, double value, CompareOutcome& outcome) {
  const auto it = std::find_if(std::begin(kMetrics), std::end(kMetrics), [&](const auto& m) { return name == m.first; });
  outcome.metrics.push_back({name, value, it->second});
}

/// The metrics of kMetrics but the timings.
void add_metrics(const pbd_study::PbdStudy& study, const Steady& steady, const Strip& st, const Samples& samples,
                 const fem_reference::FemResult& fem, CompareOutcome& outcome) {
  auto add = [&](const std::string& name, double value) { add_metric(name, value, outcome); };
  auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  const double tip_pbd = samples.pbd_uy.back(), tip_fem = samples.fem_uy.back(), tip_eb = samples.eb_uy.back();
  const auto e_fem = relative_errors(samples.pbd_uy, samples.fem_uy);
  add("centreline.deflection.rel_l2", e_fem.rel_l2);
  add("centreline.deflection.rel_max", e_fem.rel_max);
  add("tip.deflection.rel_error", rel(tip_pbd, tip_fem));
  add("pbd.tip.euler_bernoulli.rel_error", rel(tip_pbd, tip_eb));
  add("fem.tip.euler_bernoulli.rel_error", rel(tip_fem, tip_eb));
  add("pbd.centreline.euler_bernoulli.rel_l2", relative_errors(samples.pbd_uy, samples.eb_uy).rel_l2);
  add("fem.centreline.euler_bernoulli.rel_l2", relative_errors(samples.fem_uy, samples.eb_uy).rel_l2);
  add("pbd.bending_stiffness_dev", std::abs(st.EI_pbd / st.EI - 1));
  add("pbd.load_dev", std::abs(st.W_pbd / st.W_fem - 1));
  add("pbd.steady.max_speed", steady.max_speed);
  add("pbd.steady.rel_change", steady.max_u > 0 ? steady.max_speed * study.setup.step.dt / steady.max_u : 0.0);
  add("pbd.steady.kinetic_energy", study.model.particles.kinetic_energy());
  add("pbd.steady.max_stretch", steady.max_stretch);
  add("fem.equilibrium_dev", report::fem_equilibrium_dev(fem));
}

/// summary.json's model-specific part.
nlohmann::json summary_json(const workbench::CaseFile& file, const pbd_study::PbdStudy& study, const Rod& rod,
                            const Strip& st, const Samples& samples, const fem_reference::FemProblem& problem,
                            const fem_reference::FemResult& fem) {
  const auto& setup = study.setup;
  const auto& particles = study.model.particles;
  const auto& mesh = study.mesh.mesh;
  nlohmann::json json;
  json["case"] = file.path().string();
  json["title"] = setup.title;
  json["model"] = "pbd";
  json["strip"] = {{"length", st.L}, {"height", st.D}, {"thickness", problem.thickness}, {"young", problem.young},
                   {"bending_stiffness", st.EI}, {"load_per_length", st.q}, {"end_shear", st.P}};
  json["tip_u_y"] = {{"pbd", samples.pbd_uy.back()}, {"fem", samples.fem_uy.back()}, {"euler_bernoulli", samples.eb_uy.back()}};
  json["pbd"] = {{"nodes", particles.size()}, {"segments_beyond_clamp", samples.s.size() - 1},
                 {"frames", setup.frames}, {"time_step", setup.step.dt}, {"substeps", setup.step.substeps},
                 {"iterations", setup.step.iterations}, {"damping", setup.step.damping},
                 {"bending_stiffness", st.EI_pbd}, {"transverse_load", st.W_pbd},
                 {"tip_u_x", particles.x[rod.line.nodes.back()][0] - mesh.points[rod.line.nodes.back()][0]}};
  json["fem"] = {{"solver", fem.solver}, {"iterations", fem.iterations}, {"residual", fem.residual},
                 {"backward_error", fem.backward_error ? nlohmann::json(*fem.backward_error) : nlohmann::json()},
                 {"dofs", fem.n_dofs}, {"degree", fem.degree}, {"model", fem.model}, {"cells", fem.n_active_cells},
                 {"transverse_load", st.W_fem}};
  return json;
}

/// summary.txt's notes.
std::vector<std::string> summary_notes(const pbd_study::PbdStudy& study, const Strip& st, const Samples& samples,
                                       const fem_reference::FemResult& fem) {
  const auto& setup = study.setup;
  const double L = st.L;
  std::ostringstream n1, n2, n3;
  n1.precision(6);
  n2.precision(6);
  n3.precision(4);
  n1 << "tip deflection u_y at s = " << L << " m: PBD " << samples.pbd_uy.back() << " m, FEM " << samples.fem_uy.back()
     << " m, Euler-Bernoulli " << samples.eb_uy.back() << " m";
  n2 << "strip: E I = " << st.EI << " N m^2 (PBD " << st.EI_pbd << "), load " << st.W_fem << " N (PBD " << st.W_pbd
     << "), |load| L^2 / E I = " << std::abs(st.W_fem) * L * L / st.EI;
  n3 << "PBD: " << samples.s.size() - 1 << " segments, " << setup.frames << " frames of " << setup.step.dt << " s, "
     << setup.step.substeps << " substeps x " << setup.step.iterations << " iterations; FEM: Q" << fem.degree << ", "
     << fem.n_active_cells << " cells, " << fem.n_dofs << " DoFs";
  return {n1.str(), n2.str(), n3.str()};
}

}  // namespace

namespace {

/// What the PBD comparison reads and checks before it runs anything.
struct PbdInput {
  pbd_study::PbdStudy study;
  fem_reference::FemProblem problem;
  Rod rod;
  double D = 0;  ///< the strip's height [m]
};

PbdInput read_pbd_input(const workbench::CaseFile& file, const CompareOptions& options) {
  const auto root = file.root();
  auto pbd_case = pbd_study::read_pbd_case(file);  // title and [pbd]
  auto problem = fem_reference::problem_from_case(file);             // [mesh], [material], [boundary], [[load]], [fem]
  report::check_gate_names(options, pbd_metric_names(), root);
  file.reject_unknown_keys();
  auto study = pbd_study::load_pbd_study(file, std::move(pbd_case));
  const Rod rod = check_rod(study, root.table("pbd"));
  const double D = strip_height(strip_extent(problem), rod, file.path().string());
  return {std::move(study), std::move(problem), rod, D};
}

}  // namespace

void check_pbd_compare(const workbench::CaseFile& file, const CompareOptions& options) { read_pbd_input(file, options); }

CompareOutcome run_pbd_compare(const workbench::CaseFile& file, const CompareOptions& options, const fs::path& dir,
                               std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  auto input = read_pbd_input(file, options);
  auto& study = input.study;
  const auto& problem = input.problem;
  const Rod& rod = input.rod;
  const double D = input.D;
  const std::string case_name = file.path().string();

  // PBD to rest: the case's frames.
  auto t = std::chrono::steady_clock::now();
  fs::create_directories(dir / "pbd");
  pbd_study::write_pbd_outputs(study, dir / "pbd", false, log);
  const double pbd_seconds = seconds_since(t);
  const Steady steady = steady_state(study);

  // FEM once.
  double fem_seconds = 0;
  const auto fem = report::run_fem(problem, dir, log, fem_seconds);
  t = std::chrono::steady_clock::now();
  if (fem.dim != 2) throw Error(case_name + ": model = \"pbd\" compares with a 2D FEM strip (plane stress), got a 3D mesh");
  const Strip st = strip(problem, study, rod, D);
  Samples samples = sample_centreline(study, rod, st, fem, case_name, dir);

  CompareOutcome outcome;
  add_metrics(study, steady, st, samples, fem, outcome);
  add_metric("time.pbd_s", pbd_seconds, outcome);
  add_metric("time.fem_s", fem_seconds, outcome);
  add_metric("time.compare_s", seconds_since(t), outcome);
  const std::string title = study.setup.title.empty() ? file.path().stem().string() : study.setup.title;
  double figures_seconds = 0;
  if (options.figures) {
    t = std::chrono::steady_clock::now();
    report::run_figure_script("compare/pbd_figures.py", dir, title, options.figure_formats, log);
    figures_seconds = seconds_since(t);
  }
  add_metric("time.figures_s", figures_seconds, outcome);
  add_metric("time.total_s", seconds_since(start), outcome);

  auto json = summary_json(file, study, rod, st, samples, problem, fem);
  auto notes = summary_notes(study, st, samples, fem);
  outcome.fields.lines.emplace_back("centreline", centreline_table(std::move(samples)));
  report::finish(dir, file.path(), std::move(json), options.gate, notes, outcome, log);
  return outcome;
}

}  // namespace compare
