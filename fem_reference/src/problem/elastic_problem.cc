// The elastic problem (see elastic_problem.h): run() with its phases in order, and what follows the
// solution: reactions, the backward error of a solve above the tolerance, element stresses and nodal
// displacements, probes, errors against an exact solution, the VTU; solve_on_mesh, the entry point.
#include "problem/elastic_problem.h"

#include "mpi/runtime.h"

#include <workbench/error.h>
#include <workbench/symmetric_tensor.h>
#include <workbench/vtk_output.h>

#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/grid/grid_tools_cache.h>
#include <deal.II/numerics/vector_tools.h>

#include <sys/resource.h>

#include <cctype>
#include <cmath>
#include <set>
#include <sstream>

namespace fem_reference {

namespace fs = std::filesystem;
using namespace dealii;
using workbench::Error;

namespace {

/// The largest backward error a solution may have (see ElasticProblem::backward_error): a
/// backward-stable solve leaves about 1e-16, CG stopped on its recursive residual somewhat more.
constexpr double kBackwardErrorLimit = 1e-12;

/// One line out of a deal.II exception: its "Additional information", else its name.
std::string one_line(const ExceptionBase& e) {
  std::string text = e.what();
  const std::string marker = "Additional information:";
  auto pos = text.find(marker);
  text = pos == std::string::npos ? e.get_exc_name() : text.substr(pos + marker.size());
  std::string out;
  bool space = false;
  for (char c : text) {
    if (std::isspace(static_cast<unsigned char>(c))) {
      space = !out.empty();
    } else {
      if (space) out += ' ';
      out += c;
      space = false;
    }
  }
  return out;
}

const char* kind_name(SupportKind k) {
  return k == SupportKind::Clamped ? "clamped" : k == SupportKind::Roller ? "roller" : "displacement";
}

bool all_finite(const TrilinosWrappers::MPI::Vector& v) {
  for (const double x : v) if (!std::isfinite(x)) return false;
  return true;
}

template <class Container>
bool all_finite(const Container& v) {
  return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); });
}

}  // namespace

template <int dim>
ElasticProblem<dim>::ElasticProblem(const FemProblem& problem, const PlainMesh& mesh, std::ostream* log)
    : problem_(problem), mesh_(mesh), mode_frame_(ModeFrame::of_nodes(mesh.nodes, dim)), log_(log),
      degree_(problem.options.degree) {
  const double E = problem.young, nu = problem.poisson;
  mu_ = E / (2 * (1 + nu));
  lambda_solid_ = E * nu / ((1 + nu) * (1 - 2 * nu));
  lambda_ = lambda_solid_;
  if (dim == 2) {
    thickness_ = problem.thickness;
    if (problem.options.model == Model::PlaneStress) lambda_ = 2 * lambda_solid_ * mu_ / (lambda_solid_ + 2 * mu_);
  }
}

template <int dim>
void ElasticProblem<dim>::require_finite(bool finite, const std::string& what) const {
  if (Utilities::MPI::min(int(finite), comm_) == 1) return;
  double load = 0;
  for (const auto& t : problem_.tractions)
    for (double f : t.force) load = std::max(load, std::abs(f));
  for (const auto& p : problem_.point_forces)
    for (double f : p.force) load = std::max(load, std::abs(f));
  double body = 0;
  for (double b : problem_.body_force) body = std::max(body, std::abs(b));
  // Loads beyond 1e150 overflow on their own; else the stiffness (young) is out of range.
  const std::string key = !(body <= 1e150) ? "fem.body_force" : !(load <= 1e150) ? "load" : "material.young";
  std::ostringstream s;
  s << problem_.name << ": " << key << ": the " << what
    << " is not finite (it overflows double precision) with material.young = " << problem_.young
    << " Pa and loads up to " << std::max(load, body) << " (N, N/m^3); give values in SI units (Pa, N) within a sane range";
  throw Error(s.str());
}

/// r = K u - f assembled element by element without constraints. With `bound`, over every cell,
/// and bound = sum over the elements of |K_e| |u_e| + |f_e|; without, only over the cells touching
/// a constrained DoF (enough for the reactions).
template <int dim>
void ElasticProblem<dim>::element_residual(TrilinosWrappers::MPI::Vector& residual,
                                           TrilinosWrappers::MPI::Vector* bound) {
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FEFaceValues<dim> fe_face_values(*mapping_, *fe_, *face_quadrature_,
                                   update_values | update_quadrature_points | update_JxW_values);
  const unsigned n = fe_->n_dofs_per_cell();
  FullMatrix<double> cell_matrix(n, n);
  Vector<double> cell_rhs(n), u(n), r(n), scale(n);
  std::vector<types::global_dof_index> dofs(n);
  residual.reinit(owned_, comm_);
  if (bound) bound->reinit(owned_, comm_);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell->get_dof_indices(dofs);
    if (!bound && std::none_of(dofs.begin(), dofs.end(), [&](auto d) { return constraints_.is_constrained(d); }))
      continue;
    cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs);
    for (unsigned i = 0; i < n; ++i) u(i) = ghosted_(dofs[i]);
    cell_matrix.vmult(r, u);
    r -= cell_rhs;
    residual.add(dofs, r);
    if (!bound) continue;
    for (unsigned i = 0; i < n; ++i) {
      scale(i) = std::abs(cell_rhs(i));
      for (unsigned j = 0; j < n; ++j) scale(i) += std::abs(cell_matrix(i, j) * u(j));
    }
    bound->add(dofs, scale);
  }
  for (const auto& [dof, value] : point_loads_) {
    residual(dof) -= value;
    if (bound) (*bound)(dof) += std::abs(value);
  }
  residual.compress(VectorOperation::add);
  if (bound) bound->compress(VectorOperation::add);
}

/// max_i |f - K u|_i / (|K| |u| + |f|)_i over the unconstrained DoFs, with |K| |u| summed element
/// by element (an upper bound of the assembled product). Near 1e-16, u solves K u = f to within
/// rounding of K's entries, as a direct solve does. Then a relative residual ||K u - f|| / ||f||
/// above the tolerance is the rounding floor of an ill-conditioned system (a thin bending strip:
/// K u cancels terms of E t |u| to leave loads many orders smaller), not an unconverged or failed
/// solve; the solution is then as accurate as the conditioning allows in double precision.
template <int dim>
double ElasticProblem<dim>::backward_error() {
  TrilinosWrappers::MPI::Vector residual, bound;
  element_residual(residual, &bound);
  double worst = 0;
  for (const auto i : owned_)
    if (!constraints_.is_constrained(i) && bound(i) > 0) worst = std::max(worst, std::abs(residual(i)) / bound(i));
  return Utilities::MPI::max(worst, comm_);
}

/// Reactions: r = K u - f assembled without constraints, summed over each support's DoFs (a DoF
/// shared by two supports counts for the first).
template <int dim>
void ElasticProblem<dim>::compute_reactions() {
  TrilinosWrappers::MPI::Vector residual;
  element_residual(residual, nullptr);

  std::set<types::global_dof_index> claimed;
  std::vector<double> forces(problem_.supports.size() * 3, 0.0);
  std::vector<types::global_dof_index> face_dofs;
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    const auto comps = constrained_components(problem_.supports[s]);
    for_each_boundary_face([&](const auto& cell, unsigned f, types::boundary_id id) {
      if (!carries(id, support_group_[s])) return;
      face_dofs.resize(fe_->n_dofs_per_face(f));
      cell->face(f)->get_dof_indices(face_dofs);
      for (unsigned i = 0; i < face_dofs.size(); ++i) {
        const int c = fe_->face_system_to_component_index(i, f).first;
        if (std::find(comps.begin(), comps.end(), c) == comps.end()) continue;
        if (!owned_.is_element(face_dofs[i]) || !claimed.insert(face_dofs[i]).second) continue;
        forces[3 * s + c] += residual(face_dofs[i]);
      }
    });
  }
  Utilities::MPI::sum(forces, comm_, forces);
  result_.reactions.clear();
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    GroupReaction g{problem_.supports[s].group, kind_name(problem_.supports[s].kind), {}};
    for (int a = 0; a < dim; ++a) g.force[a] = forces[3 * s + a] * thickness_;
    result_.reactions.push_back(g);
  }
}

/// Per-element (gmsh order) averages of the stress over the element's active descendants, nodal
/// displacements at the gmsh nodes, per-active-cell fields for the VTU.
template <int dim>
void ElasticProblem<dim>::postprocess() {
  const std::size_t n_el = mesh_.cell_count();
  constexpr int K = 10;  // volume, centre x y z, sx sy sz txy tyz txz
  std::vector<double> acc(n_el * K, 0.0);
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_, update_gradients | update_quadrature_points | update_JxW_values);
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<2, dim>> grads(quadrature_->size());
  cell_fields_.assign(7, Vector<float>(tria_->n_active_cells()));
  using workbench::von_mises;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    fe_values.reinit(cell);
    fe_values[displacement].get_function_gradients(ghosted_, grads);
    double local[K] = {};
    for (unsigned q = 0; q < grads.size(); ++q) {
      const double JxW = fe_values.JxW(q);
      double s[6];  // xx yy zz xy yz xz
      stress_of(grads[q], s);
      local[0] += JxW;
      for (int a = 0; a < dim; ++a) local[1 + a] += JxW * fe_values.quadrature_point(q)[a];
      for (int k = 0; k < 6; ++k) local[4 + k] += JxW * s[k];
    }
    double avg[6];
    for (int k = 0; k < 6; ++k) avg[k] = local[4 + k] / local[0];
    for (int k = 0; k < 6; ++k) cell_fields_[k][cell->active_cell_index()] = float(avg[k]);
    cell_fields_[6][cell->active_cell_index()] = float(von_mises(avg));
    typename Triangulation<dim>::cell_iterator coarse = cell;
    while (coarse->level() > 0) coarse = coarse->parent();
    const std::size_t e = coarse->index();
    for (int k = 0; k < K; ++k) acc[e * K + k] += local[k];
  }
  Utilities::MPI::sum(acc, comm_, acc);

  auto& r = result_;
  r.cell_centres.assign(3 * n_el, 0.0);
  for (auto* v : {&r.sigma_x, &r.sigma_y, &r.sigma_z, &r.tau_xy, &r.tau_yz, &r.tau_xz, &r.von_mises}) v->assign(n_el, 0.0);
  for (std::size_t e = 0; e < n_el; ++e) {
    const double* a = &acc[e * K];
    const double vol = a[0] > 0 ? a[0] : 1.0;
    for (int k = 0; k < dim; ++k) r.cell_centres[3 * e + k] = a[1 + k] / vol;
    double s[6];
    for (int k = 0; k < 6; ++k) s[k] = a[4 + k] / vol;
    r.sigma_x[e] = s[0];
    r.sigma_y[e] = s[1];
    r.sigma_z[e] = s[2];
    r.tau_xy[e] = s[3];
    r.tau_yz[e] = s[4];
    r.tau_xz[e] = s[5];
    r.von_mises[e] = von_mises(s);
  }

  const std::size_t n_nodes = mesh_.node_count();
  std::vector<double> u(n_nodes * (dim + 1), 0.0);
  std::vector<char> seen(n_nodes, 0);
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      const auto vi = cell->vertex_index(v);
      if (vi >= n_nodes || seen[vi]) continue;
      seen[vi] = 1;
      for (int c = 0; c < dim; ++c) u[vi * (dim + 1) + c] = ghosted_(cell->vertex_dof_index(v, c));
      u[vi * (dim + 1) + dim] = 1;
    }
  }
  Utilities::MPI::sum(u, comm_, u);
  r.node_points = mesh_.nodes;
  r.node_displacement.assign(n_nodes * dim, 0.0);
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double count = u[i * (dim + 1) + dim];
    for (int c = 0; c < dim; ++c) r.node_displacement[i * dim + c] = count > 0 ? u[i * (dim + 1) + c] / count : 0.0;
  }
}

template <int dim>
void ElasticProblem<dim>::stress_of(const Tensor<2, dim>& g, double* s) const {
  double tr = 0;
  for (int a = 0; a < dim; ++a) tr += g[a][a];
  s[0] = lambda_ * tr + 2 * mu_ * g[0][0];
  s[1] = lambda_ * tr + 2 * mu_ * g[1][1];
  s[3] = mu_ * (g[0][1] + g[1][0]);
  if (dim == 3) {
    s[2] = lambda_ * tr + 2 * mu_ * g[dim - 1][dim - 1];
    s[4] = mu_ * (g[1][dim - 1] + g[dim - 1][1]);
    s[5] = mu_ * (g[0][dim - 1] + g[dim - 1][0]);
  } else {
    s[2] = problem_.options.model == Model::PlaneStrain ? lambda_solid_ * tr : 0.0;
    s[4] = s[5] = 0;
  }
}

/// Each probe point located in the mesh (a bounding-box tree, GridTools::Cache), the solution's
/// value and gradient there from FEValues on a one-point quadrature at its unit-cell position.
template <int dim>
void ElasticProblem<dim>::evaluate_probes() {
  const auto& points = problem_.probe_points;
  if (points.empty()) return;
  constexpr int K = 1 + 3 + 6;  // found, u, sigma
  std::vector<double> acc(points.size() * K, 0.0);
  GridTools::Cache<dim> cache(*tria_, *mapping_);
  typename Triangulation<dim>::active_cell_iterator hint;
  const FEValuesExtractors::Vector displacement(0);
  std::vector<Tensor<1, dim>> value(1);
  std::vector<Tensor<2, dim>> grad(1);
  for (std::size_t i = 0; i < points.size(); ++i) {
    Point<dim> p;
    for (int a = 0; a < dim; ++a) p[a] = points[i][a];
    const auto [cell, unit] = GridTools::find_active_cell_around_point(cache, p, hint);
    if (cell == tria_->end() || !cell->is_locally_owned()) continue;
    hint = cell;
    const typename DoFHandler<dim>::active_cell_iterator dof_cell(&*tria_, cell->level(), cell->index(), &dof_handler_);
    const Quadrature<dim> at(mesh_.simplex ? unit : GeometryInfo<dim>::project_to_unit_cell(unit));
    FEValues<dim> fe_values(*mapping_, *fe_, at, update_values | update_gradients);
    fe_values.reinit(dof_cell);
    fe_values[displacement].get_function_values(ghosted_, value);
    fe_values[displacement].get_function_gradients(ghosted_, grad);
    double* out = &acc[i * K];
    out[0] = 1;
    for (int a = 0; a < dim; ++a) out[1 + a] = value[0][a];
    stress_of(grad[0], out + 4);
  }
  Utilities::MPI::sum(acc, comm_, acc);
  result_.probes.assign(points.size(), {});
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double* in = &acc[i * K];
    if (in[0] == 0) continue;
    auto& probe = result_.probes[i];
    probe.found = true;
    for (int a = 0; a < 3; ++a) probe.u[a] = in[1 + a] / in[0];
    for (int k = 0; k < 6; ++k) probe.sigma[k] = in[4 + k] / in[0];
  }
}

template <int dim>
void ElasticProblem<dim>::compute_errors() {
  if (!problem_.exact_displacement) return;
  PlainFunction<dim> exact(problem_.exact_displacement, problem_.exact_gradient);
  std::unique_ptr<Quadrature<dim>> q;
  if (mesh_.simplex)
    q = std::make_unique<QGaussSimplex<dim>>(degree_ + 2);
  else
    q = std::make_unique<QGauss<dim>>(degree_ + 2);
  Vector<float> cell_errors(tria_->n_active_cells());
  VectorTools::integrate_difference(*mapping_, dof_handler_, ghosted_, exact, cell_errors, *q, VectorTools::L2_norm);
  result_.l2_error = VectorTools::compute_global_error(*tria_, cell_errors, VectorTools::L2_norm);
  if (problem_.exact_gradient) {
    VectorTools::integrate_difference(*mapping_, dof_handler_, ghosted_, exact, cell_errors, *q,
                                      VectorTools::H1_seminorm);
    result_.h1_error = VectorTools::compute_global_error(*tria_, cell_errors, VectorTools::H1_seminorm);
  }
}

template <int dim>
void ElasticProblem<dim>::write_vtu(const fs::path& dir) {
  // One VTK cell per active cell on shared vertices: the element-constant stresses as cell data,
  // the displacement at the vertices. Linear cells for every degree and cell shape alike (Q2 and
  // P2 show their vertex values; docs/fem-reference.md).
  const int ranks = int(Utilities::MPI::n_mpi_processes(comm_));
  workbench::OutputMesh out;
  std::vector<long long> point_of_vertex(tria_->n_vertices(), -1);
  workbench::Field u{"displacement [m]", 3, {}, {"x", "y", "z"}, {}};
  const char* stress_names[7] = {"sigma_x", "sigma_y", "sigma_z", "tau_xy", "tau_yz", "tau_xz", "von_mises"};
  std::vector<int> stresses;
  for (int k = 0; k < 7; ++k)
    if (dim == 3 || (k != 4 && k != 5)) stresses.push_back(k);
  std::vector<workbench::Field> cell_data;
  for (int k : stresses) cell_data.push_back({std::string(stress_names[k]) + " [Pa]", 1, {}, {}, {}});
  if (ranks > 1) cell_data.push_back({"rank [-]", 1, {}, {}, {}});
  // deal.II numbers quadrilateral/hexahedron vertices lexicographically, VTK counter-clockwise.
  const std::vector<unsigned> quad{0, 1, 3, 2}, hex{0, 1, 3, 2, 4, 5, 7, 6};
  std::vector<long long> ids;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    ids.clear();
    for (unsigned v = 0; v < cell->n_vertices(); ++v) {
      const unsigned w = mesh_.simplex ? v : (dim == 2 ? quad[v] : hex[v]);
      auto& point = point_of_vertex[cell->vertex_index(w)];
      if (point < 0) {
        point = (long long)out.point_count();
        const auto x = cell->vertex(w);
        for (int c = 0; c < 3; ++c) out.points.push_back(c < dim ? x[c] : 0.0);
        for (int c = 0; c < 3; ++c) u.values.push_back(c < dim ? double(ghosted_(cell->vertex_dof_index(w, c))) : 0.0);
      }
      ids.push_back(point);
    }
    const int type = mesh_.simplex ? (dim == 2 ? 5 : 10) : (dim == 2 ? 9 : 12);  // triangle, tetra, quad, hexahedron
    out.add_cell(type, ids);
    for (std::size_t f = 0; f < stresses.size(); ++f)
      cell_data[f].values.push_back(cell_fields_[stresses[f]][cell->active_cell_index()]);
    if (ranks > 1) cell_data.back().values.push_back(double(tria_->locally_owned_subdomain()));
  }
  const unsigned rank = Utilities::MPI::this_mpi_process(comm_);
  std::string name = "fem_000.vtu";
  if (ranks == 1) {
    workbench::write_vtu(dir / name, out, {u}, cell_data);
  } else {
    workbench::write_vtu(dir / ("fem_000." + std::to_string(rank) + ".vtu"), out, {u}, cell_data);
    name = "fem_000.pvtu";
    std::vector<std::string> pieces;
    for (int r = 0; r < ranks; ++r) pieces.push_back("fem_000." + std::to_string(r) + ".vtu");
    if (rank == 0) workbench::write_pvtu(dir / name, pieces, {u}, cell_data);
  }
  if (rank == 0) workbench::write_pvd(dir / "fem.pvd", {{1.0, name}});
}

template <int dim>
FemResult ElasticProblem<dim>::run(const fs::path& output_dir) {
  timer_.enter_subsection("setup");
  make_grid();
  setup_system();
  result_.dim = dim;
  result_.degree = degree_;
  result_.model = dim == 3 ? "3d" : problem_.options.model == Model::PlaneStress ? "plane_stress" : "plane_strain";
  result_.cells = mesh_.simplex ? (dim == 2 ? "triangle" : "tetrahedron") : (dim == 2 ? "quadrilateral" : "hexahedron");
  result_.ranks = int(Utilities::MPI::n_mpi_processes(comm_));
  result_.n_dofs = dof_handler_.n_dofs();
  result_.n_active_cells = tria_->n_global_active_cells();
  check_rigid_motion();
  timer_.leave_subsection("setup");
  result_.setup_seconds = seconds("setup");
  std::ostringstream line;
  line << result_.n_dofs << " DoFs, " << result_.n_active_cells << " cells (" << (mesh_.simplex ? "P" : "Q") << degree_
       << ", " << result_.model << ", " << result_.ranks << " rank" << (result_.ranks > 1 ? "s" : "") << "), setup "
       << result_.setup_seconds << " s";
  say(line.str());

  require_finite(std::isfinite(lambda_) && std::isfinite(mu_) && std::isfinite(lambda_solid_), "stiffness (Lame coefficients)");
  timer_.enter_subsection("assemble");
  assemble_system();
  require_finite(all_finite(rhs_), "load vector");
  if (!use_mg_) require_finite(std::isfinite(matrix_.linfty_norm()), "stiffness matrix");
  timer_.leave_subsection("assemble");
  result_.assemble_seconds = seconds("assemble");
  say("assembled in " + std::to_string(result_.assemble_seconds) + " s");

  timer_.enter_subsection("solve");
  solve();
  require_finite(all_finite(solution_) && std::isfinite(result_.residual), "displacement");
  timer_.leave_subsection("solve");
  result_.solve_seconds = seconds("solve");
  {
    std::ostringstream s;
    s << "solved with " << result_.solver << ": " << result_.iterations << " iterations, relative residual "
      << result_.residual << " (" << result_.solve_seconds << " s)";
    say(s.str());
  }
  // With the coarser level, the fine CG stops at coarser_share of where it started, if that is higher.
  double accepted = problem_.options.tolerance;
  if (coarser_.size() > 0) {
    const auto& c = coarser_outcome_;
    accepted = std::max(accepted, problem_.options.coarser_share * c.coarser_start_residual);
    std::ostringstream s;
    s << "the coarse mesh's own solution from the multigrid hierarchy (" << c.coarser_dofs << " DoFs): "
      << c.coarser_iterations << " iterations, relative residual " << c.coarser_residual
      << "; the fine CG started from it at relative residual " << c.coarser_start_residual;
    if (problem_.options.coarser_share > 0)
      s << " and stopped at " << problem_.options.coarser_share << " of that or fem.tolerance";
    say(s.str());
  }
  if (result_.residual > accepted) {
    // Above the tolerance: the rounding floor of an ill-conditioned system, or a wrong solution.
    result_.backward_error = backward_error();
    std::ostringstream s;
    s << "relative residual " << result_.residual << " is above fem.tolerance " << accepted
      << "; backward error " << *result_.backward_error;
    if (*result_.backward_error > kBackwardErrorLimit) {
      s << " (> " << kBackwardErrorLimit << "): the " << result_.solver
        << " solution is not accurate; use fem.solver = \"direct\" or check the supports";
      throw Error(problem_.name + ": " + s.str());
    }
    say(s.str() + ": the rounding floor of this ill-conditioned system (u solves K u = f to rounding)");
  }

  timer_.enter_subsection("output");
  compute_reactions();
  postprocess();
  evaluate_probes();
  compute_errors();
  result_.applied = applied_;
  {
    bool finite = all_finite(result_.node_displacement) && all_finite(result_.cell_centres);
    for (const auto* v : {&result_.sigma_x, &result_.sigma_y, &result_.sigma_z, &result_.tau_xy, &result_.tau_yz,
                          &result_.tau_xz, &result_.von_mises})
      finite = finite && all_finite(*v);
    for (const auto& g : result_.reactions)
      for (double f : g.force) finite = finite && std::isfinite(f);
    for (const auto& probe : result_.probes)
      finite = finite && all_finite(probe.u) && all_finite(probe.sigma);
    for (const auto& cell_field : cell_fields_)
      for (float x : cell_field) finite = finite && std::isfinite(x);
    require_finite(finite, "stress, displacement or reaction");
  }
  if (!output_dir.empty() && problem_.options.write_vtu)
    mpi_collective([&] {
      try {
        write_vtu(output_dir);
      } catch (const ExceptionBase& e) {  // one line, as solve_on_mesh makes of the others
        throw Error(problem_.name + ": " + output_dir.string() + ": deal.II: " + one_line(e));
      }
    });
  if (coarser_.size() > 0) result_.coarser = coarser_result();
  timer_.leave_subsection("output");
  result_.output_seconds = seconds("output");
  {
    std::ostringstream s;
    s.precision(6);
    auto vec = [&](const std::array<double, 3>& f) {
      s << "(" << f[0] << ", " << f[1];
      if (dim == 3) s << ", " << f[2];
      s << ") N";
    };
    s << "applied ";
    vec(applied_);
    for (const auto& g : result_.reactions) {
      s << "; reaction " << g.group << " ";
      vec(g.force);
    }
    say(s.str());
  }
  struct rusage usage {};
  getrusage(RUSAGE_SELF, &usage);
  result_.peak_memory_bytes = Utilities::MPI::max(double(usage.ru_maxrss) * 1024.0, comm_);
  return std::move(result_);
}

template <int dim>
std::shared_ptr<FemResult> ElasticProblem<dim>::coarser_result() {
  FemResult fine = std::move(result_);
  result_ = FemResult{};
  result_.dim = fine.dim;
  result_.degree = fine.degree;
  result_.model = fine.model;
  result_.cells = fine.cells;
  result_.ranks = fine.ranks;
  result_.n_dofs = coarser_outcome_.coarser_dofs;
  result_.n_active_cells = tria_->n_global_coarse_cells();
  result_.solver = (coarser_outcome_.coarser_iterations > 0 ? "cg with " : "direct: ") + coarser_outcome_.coarse_solver +
                   ", the multigrid's coarse level";
  result_.iterations = coarser_outcome_.coarser_iterations;
  result_.residual = coarser_outcome_.coarser_residual;
  ghosted_ = coarser_;
  postprocess();  // no reactions: the fine mesh's residual of the coarse solution is not the coarse one's
  evaluate_probes();
  result_.applied = applied_;
  bool finite = all_finite(result_.node_displacement) && std::isfinite(result_.residual);
  for (const auto* v : {&result_.sigma_x, &result_.sigma_y, &result_.sigma_z, &result_.tau_xy, &result_.tau_yz,
                        &result_.tau_xz, &result_.von_mises})
    finite = finite && all_finite(*v);
  require_finite(finite, "coarser level's stress or displacement");
  auto coarse = std::make_shared<FemResult>(std::move(result_));
  result_ = std::move(fine);
  result_.coarser_start_residual = coarser_outcome_.coarser_start_residual;
  ghosted_ = solution_;
  return coarse;
}

template class ElasticProblem<2>;
template class ElasticProblem<3>;

FemResult solve_on_mesh(const FemProblem& problem, const PlainMesh& mesh, const fs::path& output_dir,
                        std::ostream* log, double mesh_seconds) {
  ensure_mpi();
  FemResult result;
  const char* solver = "solver";
  try {
    if (mesh.dim == 2) {
      ElasticProblem<2> p(problem, mesh, log);
      result = p.run(output_dir);
    } else {
      ElasticProblem<3> p(problem, mesh, log);
      result = p.run(output_dir);
    }
  } catch (const Error&) {
    throw;
  } catch (const ExceptionBase& e) {
    throw Error(problem.name + ": " + mesh.source + ": deal.II: " + one_line(e));
  } catch (const std::exception& e) {
    throw Error(problem.name + ": " + e.what());
  } catch (int code) {
    throw Error(problem.name + ": the Trilinos " + solver + " failed (error code " + std::to_string(code) + ")");
  }
  result.mesh_seconds = mesh_seconds;
  return result;
}

}  // namespace fem_reference
