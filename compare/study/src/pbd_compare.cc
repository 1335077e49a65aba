// The PBD angle bending rod against the deal.II FEM strip (docs/compare.md "model = pbd"):
// PBD relaxed to rest from the case's frames, FEM solved once, the FEM displacement sampled on the
// strip's mid-height line at the PBD centreline's nodes, both against Euler-Bernoulli.
#include <compare/pbd_compare.h>
#include <compare/metrics.h>

#include "report.h"

#include <fem_reference/fem_case.h>
#include <gmsh.h>
#include <gmsh_session.h>
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

/// The FEM displacement (u_x, u_y) at points of the strip: linear in x along the row of mesh nodes
/// at the point's height, or between the two rows around it (a structured strip: rows of nodes at
/// constant y, e.g. tests/fem/meshes/strip.geo).
class RowSampler {
 public:
  RowSampler(const fem_reference::FemResult& fem, double tol) : tol_(tol) {
    std::vector<std::size_t> order(fem.node_count());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(),
              [&](std::size_t a, std::size_t b) { return fem.node_points[3 * a + 1] < fem.node_points[3 * b + 1]; });
    for (std::size_t i : order) {
      const double y = fem.node_points[3 * i + 1];
      if (rows_.empty() || y - rows_.back().y > tol_) rows_.push_back({y, {}});
      rows_.back().nodes.push_back({fem.node_points[3 * i], fem.node_displacement[2 * i], fem.node_displacement[2 * i + 1]});
    }
    for (auto& r : rows_) std::sort(r.nodes.begin(), r.nodes.end(), [](const Node& a, const Node& b) { return a.x < b.x; });
  }

  /// u_x, u_y at (x, y); throws workbench::Error outside the rows.
  std::array<double, 2> at(double x, double y) const {
    for (std::size_t r = 0; r < rows_.size(); ++r) {
      if (std::abs(rows_[r].y - y) <= tol_) return along(rows_[r], x);
      if (r + 1 < rows_.size() && rows_[r].y < y && y < rows_[r + 1].y) {
        const double t = (y - rows_[r].y) / (rows_[r + 1].y - rows_[r].y);
        const auto a = along(rows_[r], x), b = along(rows_[r + 1], x);
        return {(1 - t) * a[0] + t * b[0], (1 - t) * a[1] + t * b[1]};
      }
    }
    throw Error("no FEM mesh nodes around y = " + std::to_string(y));
  }

 private:
  struct Node {
    double x, ux, uy;
  };
  struct Row {
    double y;
    std::vector<Node> nodes;
  };
  std::array<double, 2> along(const Row& row, double x) const {
    const auto& n = row.nodes;
    if (n.empty() || x < n.front().x - tol_ || x > n.back().x + tol_)
      throw Error("the FEM row of nodes at y = " + std::to_string(row.y) + " does not reach x = " + std::to_string(x));
    auto it = std::lower_bound(n.begin(), n.end(), x, [](const Node& a, double v) { return a.x < v; });
    if (it == n.end()) return {n.back().ux, n.back().uy};
    if (std::abs(it->x - x) <= tol_ || it == n.begin()) return {it->ux, it->uy};
    const auto& a = *(it - 1);
    const double t = (x - a.x) / (it->x - a.x);
    return {(1 - t) * a.ux + t * it->ux, (1 - t) * a.uy + t * it->uy};
  }
  double tol_;
  std::vector<Row> rows_;
};

}  // namespace

std::vector<std::string> pbd_metric_names() {
  std::vector<std::string> names;
  for (const auto& [name, meaning] : kMetrics) names.push_back(name);
  return names;
}

namespace {

/// The PBD rod: a straight chain of line cells along +x, clamped at s = 0 (else bad input at
/// pbd.mesh).
struct Rod {
  pbd_study::Centreline line;
  double L = 0;              ///< its length beyond the clamp [m]
  pbd::Vec3 root_point;      ///< the node at s = 0 (after the ghost node inside the clamp)
};

Rod check_rod(const pbd_study::PbdStudy& study, const workbench::CaseTable& pbd_table) {
  const auto& mesh = study.mesh.mesh;
  Rod rod{pbd_study::centreline(mesh, study.pinned), 0, {}};
  const auto& line = rod.line;
  if (line.empty())
    pbd_table.fail("mesh", "model = \"pbd\" compares a rod: the mesh must be one open chain of line cells");
  const std::size_t n_line = line.nodes.size();
  const double L = rod.L = line.s.back();
  if (!(L > 0)) pbd_table.fail("mesh", "the rod has no length beyond its clamp");
  std::size_t clamp = 0;
  while (clamp + 1 < n_line && line.s[clamp] < 0) ++clamp;
  rod.root_point = mesh.points[line.nodes[clamp]];
  for (std::size_t k = 0; k < n_line; ++k) {
    const pbd::Vec3 expect = rod.root_point + pbd::Vec3(line.s[k], 0, 0);
    if ((mesh.points[line.nodes[k]] - expect).norm() > 1e-9 * L)
      pbd_table.fail("mesh", "model = \"pbd\" compares a straight rod along +x from its clamp (node " +
                                 std::to_string(line.nodes[k]) + " is off that line)");
  }
  return rod;
}

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

/// The FEM strip's extent per axis (x, y: lo, hi) from the mesh it will be solved on, read before
/// either model runs (the box, or the mesh file loaded as the FEM loads it).
std::array<std::array<double, 2>, 2> strip_extent(const fem_reference::FemProblem& problem) {
  if (problem.box) return {{{problem.box->lo[0], problem.box->hi[0]}, {problem.box->lo[1], problem.box->hi[1]}}};
  workbench::gmsh_load(problem.mesh_file, problem.mesh_parameters, problem.mesh_unit);
  std::vector<std::size_t> tags;
  std::vector<double> xyz, parametric;
  gmsh::model::mesh::getNodes(tags, xyz, parametric);
  std::array<std::array<double, 2>, 2> box{{{1e308, -1e308}, {1e308, -1e308}}};
  for (std::size_t i = 0; i + 2 < xyz.size(); i += 3)
    for (int a = 0; a < 2; ++a) {
      box[a][0] = std::min(box[a][0], xyz[i + a]);
      box[a][1] = std::max(box[a][1], xyz[i + a]);
    }
  return box;
}

/// The FEM strip's height D from its extent, after checking that it is the rod's strip: x from the
/// clamp over L, the rod at mid-height. Before any solve: two bodies are an error, not a bad score.
double strip_height(const std::array<std::array<double, 2>, 2>& extent, const Rod& rod, const std::string& case_name) {
  const double lo[2] = {extent[0][0], extent[1][0]}, hi[2] = {extent[0][1], extent[1][1]};
  const double L = rod.L;
  const double L_fem = hi[0] - lo[0], D = hi[1] - lo[1], y_mid = 0.5 * (lo[1] + hi[1]);
  std::ostringstream geometry;
  geometry.precision(6);
  if (std::abs(L_fem - L) > 1e-6 * L || std::abs(rod.root_point[0] - lo[0]) > 1e-6 * L)
    geometry << "the PBD rod spans x = " << rod.root_point[0] << " .. " << rod.root_point[0] + L
             << " m beyond its clamp, the FEM strip x = " << lo[0] << " .. " << hi[0] << " m";
  else if (std::abs(rod.root_point[1] - y_mid) > 1e-6 * D)
    geometry << "the PBD rod lies at y = " << rod.root_point[1] << " m, not at the FEM strip's mid-height y = " << y_mid << " m";
  if (!geometry.str().empty())
    throw Error(case_name + ": " + geometry.str() + " (the same strip is needed; nothing was solved)");
  return D;
}

/// The strip both models bend: Euler-Bernoulli's E I = E t D^3 / 12, q = body force * D * t,
/// P = end shear, and what the PBD case says about the same strip (its E I and transverse load).
struct Strip {
  double L = 0, D = 0, EI = 0, q = 0, P = 0, EI_pbd = 0, W_pbd = 0, W_fem = 0;
  /// Euler-Bernoulli's deflection at s.
  double eb(double s) const {
    return q * s * s * (6 * L * L - 4 * L * s + s * s) / (24 * EI) + P * s * s * (3 * L - s) / (6 * EI);
  }
};

Strip strip(const fem_reference::FemProblem& problem, const pbd_study::PbdStudy& study, const Rod& rod, double D) {
  Strip st;
  const double L = st.L = rod.L;
  st.D = D;
  st.EI = problem.young * problem.thickness * D * D * D / 12.0;
  st.q = problem.body_force[1] * D * problem.thickness;
  for (const auto& tr : problem.tractions) st.P += tr.force[1];
  for (const auto& pf : problem.point_forces) st.P += pf.force[1];
  const auto& setup = study.setup;
  const auto& mesh = study.mesh.mesh;
  const auto& particles = study.model.particles;
  st.EI_pbd = setup.model.bending_stiffness;
  if (!(st.EI_pbd > 0))
    st.EI_pbd = setup.model.bending_compliance > 0 ? (L / double(rod.line.nodes.size() - 1)) / setup.model.bending_compliance
                                                   : std::numeric_limits<double>::infinity();
  double W_pbd = 0, carrying = 0;
  std::size_t n_free = 0;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (particles.w[i] > 0) {
      ++n_free;
      W_pbd += setup.step.gravity[1] / particles.w[i];
    }
  if (setup.model.masses == pbd::ModelOptions::Masses::Lumped) {
    // total_mass sits on the cells with a free node; the rod beyond the clamp is L long.
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      const int a = mesh.cell_nodes[mesh.cell_offsets[c]], b = mesh.cell_nodes[mesh.cell_offsets[c] + 1];
      if (particles.w[a] > 0 || particles.w[b] > 0) carrying += (mesh.points[a] - mesh.points[b]).norm();
    }
    W_pbd = setup.model.total_mass * setup.step.gravity[1] * L / carrying;
  }
  st.W_pbd = W_pbd + double(n_free) * setup.step.node_force[1];
  st.W_fem = st.q * L + st.P;
  return st;
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
