// The PBD angle bending rod against the deal.II FEM strip (docs/compare.md "model = pbd"):
// PBD relaxed to rest from the case's frames, FEM solved once, the FEM displacement sampled on the
// strip's mid-height line at the PBD centreline's nodes, both against Euler-Bernoulli.
#include <compare/pbd_compare.h>
#include <compare/metrics.h>

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

CompareOutcome run_pbd_compare(const workbench::CaseFile& file, const CompareOptions& options, const fs::path& dir,
                               std::ostream& log) {
  const auto start = std::chrono::steady_clock::now();
  const auto root = file.root();
  auto pbd_case = pbd_study::read_pbd_case(file);  // title and [pbd]
  auto problem = fem_reference::problem_from_case(file);             // [mesh], [material], [boundary], [[load]], [fem]
  report::check_gate_names(options, pbd_metric_names(), root);
  file.reject_unknown_keys();
  auto study = pbd_study::load_pbd_study(file, std::move(pbd_case));
  const std::string case_name = file.path().string();

  // The PBD rod: a straight chain along +x, clamped at s = 0.
  const auto& mesh = study.mesh.mesh;
  const auto line = pbd_study::centreline(mesh, study.pinned);
  const auto pbd_table = root.table("pbd");
  if (line.empty())
    pbd_table.fail("mesh", "model = \"pbd\" compares a rod: the mesh must be one open chain of line cells");
  const std::size_t n_line = line.nodes.size();
  const double L = line.s.back();
  if (!(L > 0)) pbd_table.fail("mesh", "the rod has no length beyond its clamp");
  std::size_t clamp = 0;  // the node at s = 0 (after the ghost node inside the clamp)
  while (clamp + 1 < n_line && line.s[clamp] < 0) ++clamp;
  const pbd::Vec3 root_point = mesh.points[line.nodes[clamp]];
  for (std::size_t k = 0; k < n_line; ++k) {
    const pbd::Vec3 expect = root_point + pbd::Vec3(line.s[k], 0, 0);
    if ((mesh.points[line.nodes[k]] - expect).norm() > 1e-9 * L)
      pbd_table.fail("mesh", "model = \"pbd\" compares a straight rod along +x from its clamp (node " +
                                 std::to_string(line.nodes[k]) + " is off that line)");
  }

  // PBD to rest: the case's frames.
  auto t = std::chrono::steady_clock::now();
  fs::create_directories(dir / "pbd");
  pbd_study::run_pbd_study(study, dir / "pbd", false, log);
  const double pbd_seconds = seconds_since(t);
  const auto& particles = study.model.particles;
  double max_speed = 0, max_u = 0;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.w[i] > 0) max_speed = std::max(max_speed, particles.v[i].norm());
    max_u = std::max(max_u, (particles.x[i] - mesh.points[i]).norm());
  }
  const double max_stretch = pbd::Solver(study.model).residuals().distance;

  // FEM once.
  double fem_seconds = 0;
  const auto fem = report::run_fem(problem, dir, log, fem_seconds);
  t = std::chrono::steady_clock::now();
  if (fem.dim != 2) throw Error(case_name + ": model = \"pbd\" compares with a 2D FEM strip (plane stress), got a 3D mesh");

  // The strip's geometry from the FEM nodes: x from the clamp, height D centred on the rod.
  double lo[2] = {1e308, 1e308}, hi[2] = {-1e308, -1e308};
  for (std::size_t i = 0; i < fem.node_count(); ++i)
    for (int a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], fem.node_points[3 * i + a]);
      hi[a] = std::max(hi[a], fem.node_points[3 * i + a]);
    }
  const double L_fem = hi[0] - lo[0], D = hi[1] - lo[1], y_mid = 0.5 * (lo[1] + hi[1]);
  std::ostringstream geometry;
  geometry.precision(6);
  if (std::abs(L_fem - L) > 1e-6 * L || std::abs(root_point[0] - lo[0]) > 1e-6 * L)
    geometry << "the PBD rod spans x = " << root_point[0] << " .. " << root_point[0] + L << " m beyond its clamp, the FEM strip x = "
             << lo[0] << " .. " << hi[0] << " m";
  else if (std::abs(root_point[1] - y_mid) > 1e-6 * D)
    geometry << "the PBD rod lies at y = " << root_point[1] << " m, not at the FEM strip's mid-height y = " << y_mid << " m";
  if (!geometry.str().empty()) throw Error(case_name + ": " + geometry.str() + " (the same strip is needed)");

  // Euler-Bernoulli for the FEM strip: E I = E t D^3 / 12, q = body force * D * t, P = end shear.
  const double EI = problem.young * problem.thickness * D * D * D / 12.0;
  const double q = problem.body_force[1] * D * problem.thickness;
  double P = 0;
  for (const auto& tr : problem.tractions) P += tr.force[1];
  for (const auto& pf : problem.point_forces) P += pf.force[1];
  auto eb = [&](double s) {
    return q * s * s * (6 * L * L - 4 * L * s + s * s) / (24 * EI) + P * s * s * (3 * L - s) / (6 * EI);
  };

  // What the PBD case says about the same strip: E I and the transverse load.
  const auto& setup = study.setup;
  double EI_pbd = setup.model.bending_stiffness;
  if (!(EI_pbd > 0))
    EI_pbd = setup.model.bending_compliance > 0 ? (L / double(n_line - 1)) / setup.model.bending_compliance
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
  W_pbd += double(n_free) * setup.step.node_force[1];
  const double W_fem = q * L + P;

  // Sample both along the centreline (s >= 0; the ghost node inside the clamp is left out).
  const RowSampler sampler(fem, 1e-6 * D);
  std::vector<double> s_used, pbd_uy, fem_uy, eb_uy;
  auto csv = open_csv(dir / "centreline.csv");
  csv << "s [m],x0 [m],y0 [m],pbd_x [m],pbd_y [m],pbd_u_x [m],pbd_u_y [m],fem_u_x [m],fem_u_y [m],eb_u_y [m]\n";
  for (std::size_t k = 0; k < n_line; ++k) {
    if (line.s[k] < -1e-12 * L) continue;
    const int node = line.nodes[k];
    const pbd::Vec3 &p0 = mesh.points[node], &p = particles.x[node];
    std::array<double, 2> uf;
    try {
      uf = sampler.at(p0[0], p0[1]);
    } catch (const Error& e) {
      throw Error(case_name + ": sampling the FEM strip at s = " + std::to_string(line.s[k]) + ": " + e.what());
    }
    s_used.push_back(line.s[k]);
    pbd_uy.push_back(p[1] - p0[1]);
    fem_uy.push_back(uf[1]);
    eb_uy.push_back(eb(line.s[k]));
    csv << line.s[k] << ',' << p0[0] << ',' << p0[1] << ',' << p[0] << ',' << p[1] << ',' << p[0] - p0[0] << ','
        << p[1] - p0[1] << ',' << uf[0] << ',' << uf[1] << ',' << eb_uy.back() << '\n';
  }
  csv.close();

  CompareOutcome outcome;
  auto add = [&](const std::string& name, double value) {
    const auto it = std::find_if(std::begin(kMetrics), std::end(kMetrics), [&](const auto& m) { return name == m.first; });
    outcome.metrics.push_back({name, value, it->second});
  };
  auto rel = [](double a, double b) { return std::abs(a - b) / std::abs(b); };
  const double tip_pbd = pbd_uy.back(), tip_fem = fem_uy.back(), tip_eb = eb_uy.back();
  const auto e_fem = relative_errors(pbd_uy, fem_uy);
  add("centreline.deflection.rel_l2", e_fem.rel_l2);
  add("centreline.deflection.rel_max", e_fem.rel_max);
  add("tip.deflection.rel_error", rel(tip_pbd, tip_fem));
  add("pbd.tip.euler_bernoulli.rel_error", rel(tip_pbd, tip_eb));
  add("fem.tip.euler_bernoulli.rel_error", rel(tip_fem, tip_eb));
  add("pbd.centreline.euler_bernoulli.rel_l2", relative_errors(pbd_uy, eb_uy).rel_l2);
  add("fem.centreline.euler_bernoulli.rel_l2", relative_errors(fem_uy, eb_uy).rel_l2);
  add("pbd.bending_stiffness_dev", std::abs(EI_pbd / EI - 1));
  add("pbd.load_dev", std::abs(W_pbd / W_fem - 1));
  add("pbd.steady.max_speed", max_speed);
  add("pbd.steady.rel_change", max_u > 0 ? max_speed * setup.step.dt / max_u : 0.0);
  add("pbd.steady.kinetic_energy", particles.kinetic_energy());
  add("pbd.steady.max_stretch", max_stretch);
  add("fem.equilibrium_dev", report::fem_equilibrium_dev(fem));
  add("time.pbd_s", pbd_seconds);
  add("time.fem_s", fem_seconds);
  add("time.compare_s", seconds_since(t));

  const std::string title = setup.title.empty() ? file.path().stem().string() : setup.title;
  double figures_seconds = 0;
  if (options.figures) {
    t = std::chrono::steady_clock::now();
    report::run_figure_script("compare/pbd_figures.py", dir, title, options.figure_formats, log);
    figures_seconds = seconds_since(t);
  }
  add("time.figures_s", figures_seconds);
  add("time.total_s", seconds_since(start));

  nlohmann::json json;
  json["case"] = file.path().string();
  json["title"] = setup.title;
  json["model"] = "pbd";
  json["strip"] = {{"length", L}, {"height", D}, {"thickness", problem.thickness}, {"young", problem.young},
                   {"bending_stiffness", EI}, {"load_per_length", q}, {"end_shear", P}};
  json["tip_u_y"] = {{"pbd", tip_pbd}, {"fem", tip_fem}, {"euler_bernoulli", tip_eb}};
  json["pbd"] = {{"nodes", particles.size()}, {"segments_beyond_clamp", s_used.size() - 1},
                 {"frames", setup.frames}, {"time_step", setup.step.dt}, {"substeps", setup.step.substeps},
                 {"iterations", setup.step.iterations}, {"damping", setup.step.damping},
                 {"bending_stiffness", EI_pbd}, {"transverse_load", W_pbd},
                 {"tip_u_x", particles.x[line.nodes.back()][0] - mesh.points[line.nodes.back()][0]}};
  json["fem"] = {{"solver", fem.solver}, {"iterations", fem.iterations}, {"residual", fem.residual},
                 {"backward_error", fem.backward_error ? nlohmann::json(*fem.backward_error) : nlohmann::json()},
                 {"dofs", fem.n_dofs}, {"degree", fem.degree}, {"model", fem.model}, {"cells", fem.n_active_cells},
                 {"transverse_load", W_fem}};
  std::ostringstream n1, n2, n3;
  n1.precision(6);
  n2.precision(6);
  n3.precision(4);
  n1 << "tip deflection u_y at s = " << L << " m: PBD " << tip_pbd << " m, FEM " << tip_fem << " m, Euler-Bernoulli "
     << tip_eb << " m";
  n2 << "strip: E I = " << EI << " N m^2 (PBD " << EI_pbd << "), load " << W_fem << " N (PBD " << W_pbd
     << "), |load| L^2 / E I = " << std::abs(W_fem) * L * L / EI;
  n3 << "PBD: " << s_used.size() - 1 << " segments, " << setup.frames << " frames of " << setup.step.dt << " s, "
     << setup.step.substeps << " substeps x " << setup.step.iterations << " iterations; FEM: Q" << fem.degree << ", "
     << fem.n_active_cells << " cells, " << fem.n_dofs << " DoFs";
  report::finish(dir, file.path(), std::move(json), options.gate, {n1.str(), n2.str(), n3.str()},
                 outcome, log);
  return outcome;
}

}  // namespace compare
