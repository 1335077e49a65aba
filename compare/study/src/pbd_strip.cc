// The PBD rod and the FEM strip it is compared with (pbd_strip.h).
#include "pbd_strip.h"

#include <gmsh.h>
#include <gmsh_session.h>
#include <workbench/error.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace compare {

using workbench::Error;

RowSampler::RowSampler(const fem_reference::FemResult& fem, double tol) : tol_(tol) {
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

std::array<double, 2> RowSampler::at(double x, double y) const {
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

std::array<double, 2> RowSampler::along(const Row& row, double x) const {
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

}  // namespace compare
