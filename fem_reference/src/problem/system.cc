// The elastic problem from the mesh to the solution (see elastic_problem.h): the grid and its
// boundary ids, DoFs and constraints, the check that the supports hold the body, the element
// system and its assembly (or, for the multigrid, the right-hand side alone), and the solvers.
#include "problem/elastic_problem.h"

#include "direct/direct_solver.h"
#include "elasticity.h"
#include "mg/mg_solver.h"

#include <workbench/error.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_renumbering.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/vector_tools.h>

#include <Eigen/Eigenvalues>

#include <cmath>
#include <map>
#include <set>
#include <sstream>

namespace fem_reference {

using namespace dealii;
using workbench::Error;

namespace {

std::string no_convergence(const FemProblem& problem, const char* preconditioner,
                           const SolverControl::NoConvergence& e) {
  std::ostringstream s;
  s << problem.name << ": CG with " << preconditioner << " did not reach the relative residual "
    << problem.options.tolerance << " in " << e.last_step << " iterations (residual " << e.last_residual
    << "); raise fem.max_iterations or use fem.solver = \"direct\"";
  return s.str();
}

}  // namespace

template <int dim>
void ElasticProblem<dim>::make_grid() {
  std::vector<Point<dim>> vertices(mesh_.node_count());
  for (std::size_t i = 0; i < vertices.size(); ++i)
    for (int a = 0; a < dim; ++a) vertices[i][a] = mesh_.nodes[3 * i + a];
  std::vector<CellData<dim>> cells(mesh_.cell_count(), CellData<dim>(mesh_.corners));
  for (std::size_t c = 0; c < cells.size(); ++c)
    for (int k = 0; k < mesh_.corners; ++k) cells[c].vertices[k] = mesh_.cells[c * mesh_.corners + k];
  if (mesh_.simplex) {
    tria_ = std::make_unique<Triangulation<dim>>();
    mapping_ = std::make_unique<MappingFE<dim>>(FE_SimplexP<dim>(1));
    fe_ = std::make_unique<FESystem<dim>>(FE_SimplexP<dim>(degree_), dim);
    quadrature_ = std::make_unique<QGaussSimplex<dim>>(degree_ + 1);
    face_quadrature_ = std::make_unique<QGaussSimplex<dim - 1>>(degree_ + 1);
  } else {
    GridTools::invert_all_negative_measure_cells(vertices, cells);
    GridTools::consistently_order_cells(cells);
    if (Utilities::MPI::n_mpi_processes(comm_) > 1)
      tria_ = std::make_unique<parallel::distributed::Triangulation<dim>>(
          comm_, Triangulation<dim>::none,
          may_use_mg() ? parallel::distributed::Triangulation<dim>::construct_multigrid_hierarchy
                       : parallel::distributed::Triangulation<dim>::default_setting);
    else  // one rank: the serial triangulation refines faster and needs less memory than p4est's
      tria_ = std::make_unique<Triangulation<dim>>();
    mapping_ = std::make_unique<MappingQ<dim>>(1);
    fe_ = std::make_unique<FESystem<dim>>(FE_Q<dim>(degree_), dim);
    quadrature_ = std::make_unique<QGauss<dim>>(degree_ + 1);
    face_quadrature_ = std::make_unique<QGauss<dim - 1>>(degree_ + 1);
  }
  phase("create triangulation");
  // The coarse cells keep the order of `cells` (gmsh element order) and the vertices their indices.
  tria_->create_triangulation(vertices, cells, SubCellData());
  phase("boundary ids");

  // Boundary ids: one per distinct set of named groups a face belongs to (0: none).
  auto group_index = [&](const std::string& name) {
    auto it = std::find(groups_.begin(), groups_.end(), name);
    if (it != groups_.end()) return int(it - groups_.begin());
    groups_.push_back(name);
    return int(groups_.size() - 1);
  };
  for (const auto& s : problem_.supports) support_group_.push_back(group_index(s.group));
  for (const auto& t : problem_.tractions) traction_group_.push_back(group_index(t.group));
  std::map<std::vector<unsigned>, std::set<unsigned>> groups_of_face;
  for (unsigned g = 0; g < groups_.size(); ++g)
    for (auto face : mesh_.face_groups.at(groups_[g])) {
      std::sort(face.begin(), face.end());
      groups_of_face[face].insert(g);
    }
  std::map<std::set<unsigned>, types::boundary_id> id_of_set;
  groups_of_id_.assign(1, {});
  std::vector<std::size_t> matched(groups_.size(), 0);
  for (const auto& cell : tria_->cell_iterators_on_level(0))
    for (unsigned f = 0; f < cell->n_faces(); ++f) {
      if (!cell->face(f)->at_boundary()) continue;
      std::vector<unsigned> key;
      for (unsigned v = 0; v < cell->face(f)->n_vertices(); ++v) key.push_back(cell->face(f)->vertex_index(v));
      std::sort(key.begin(), key.end());
      auto it = groups_of_face.find(key);
      types::boundary_id id = 0;
      if (it != groups_of_face.end()) {
        auto [pos, inserted] = id_of_set.emplace(it->second, types::boundary_id(groups_of_id_.size()));
        if (inserted) groups_of_id_.emplace_back(it->second.begin(), it->second.end());
        id = pos->second;
        for (unsigned g : it->second) ++matched[g];
      }
      cell->face(f)->set_boundary_id(id);
    }
  for (unsigned g = 0; g < groups_.size(); ++g)
    if (matched[g] != mesh_.face_groups.at(groups_[g]).size())
      throw Error(problem_.name + ": group '" + groups_[g] + "' of " + mesh_.source + " has " +
                  std::to_string(mesh_.face_groups.at(groups_[g]).size() - matched[g]) +
                  " faces inside the body; supports and loads act on outer faces only");
  phase("refine");
  if (problem_.options.refine > 0) tria_->refine_global(problem_.options.refine);
  phase(nullptr);
}

template <int dim>
std::vector<int> ElasticProblem<dim>::constrained_components(const Support& s) const {
  if (s.kind == SupportKind::Roller) return {normal_axis(mesh_, s.group)};
  std::vector<int> all(dim);
  for (int c = 0; c < dim; ++c) all[c] = c;
  return all;
}

template <int dim>
void ElasticProblem<dim>::choose_solver() {
  const auto& o = problem_.options;
  // auto: direct where the factorisation is cheap (direct_is_fast); else multigrid on refined
  // meshes (its coarse level factorised or, when large, one ML cycle: in 3D 4x faster than ML on
  // the whole problem, the solver sweep) and on unrefined Q2 meshes (a single level, the p-multigrid
  // to Q1 under it: no Q2 matrix for ML), else ML (Q1 unrefined).
  direct_ = o.solver == SolverKind::Direct ||
            (o.solver == SolverKind::Auto &&
             direct_is_fast(double(dof_handler_.n_dofs()), slenderness(mesh_), o.direct_limit));
  use_mg_ = may_use_mg() && (o.solver == SolverKind::Mg ||
                             (o.solver == SolverKind::Auto && !direct_ && (o.refine > 0 || degree_ == 2)));
}

/// Numbers the DoFs cell by cell, the cells in the order of their centres (z, then y, then x):
/// in 3D the ML hierarchy depends on the DoF order, and block3d.geo's gmsh order (3 x 3 patches
/// extruded) made CG + ML 14 % slower than this one (docs/performance.md, issue 38). One rank only.
template <int dim>
void ElasticProblem<dim>::sort_dofs_by_position() {
  using Cell = typename DoFHandler<dim>::active_cell_iterator;
  std::vector<std::pair<double, Cell>> keyed;
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    double key = 0;  // frame coordinates in [-0.5, 0.5]: 1e4 apart resolves 1e4 cells per side
    for (int a = dim - 1; a >= 0; --a) key = 1e4 * key + (cell->center()[a] - mode_frame_.centre[a]) / mode_frame_.size;
    keyed.emplace_back(key, cell);
  }
  std::sort(keyed.begin(), keyed.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  std::vector<Cell> order;
  for (const auto& [key, cell] : keyed) order.push_back(cell);
  DoFRenumbering::cell_wise(dof_handler_, order);
}

template <int dim>
void ElasticProblem<dim>::setup_system() {
  phase("distribute dofs");
  dof_handler_.reinit(*tria_);
  dof_handler_.distribute_dofs(*fe_);
  choose_solver();
  if (dim == 3 && !direct_ && !use_mg_ && Utilities::MPI::n_mpi_processes(comm_) == 1) sort_dofs_by_position();
  owned_ = dof_handler_.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(dof_handler_, relevant_);
  phase("constraints");

  constraints_.clear();
  constraints_.reinit(relevant_);
  DoFTools::make_hanging_node_constraints(dof_handler_, constraints_);
  for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
    const Support& support = problem_.supports[s];
    ComponentMask mask(dim, false);
    for (int c : constrained_components(support)) mask.set(c, true);
    std::unique_ptr<Function<dim>> g;
    if (support.kind == SupportKind::Displacement)
      g = std::make_unique<PlainFunction<dim>>(support.displacement);
    else
      g = std::make_unique<Functions::ZeroFunction<dim>>(dim);
    for (types::boundary_id id = 1; id < groups_of_id_.size(); ++id)
      if (carries(id, support_group_[s]))
        VectorTools::interpolate_boundary_values(*mapping_, dof_handler_, id, *g, constraints_, mask);
  }
  constraints_.close();
  phase(nullptr);

  rhs_.reinit(owned_, comm_);
  solution_.reinit(owned_, comm_);
  ghosted_.reinit(owned_, relevant_, comm_);
  if (use_mg_) return;  // matrix-free: no sparsity pattern, no matrix
  phase("sparsity pattern");
  DynamicSparsityPattern dsp(relevant_);
  DoFTools::make_sparsity_pattern(dof_handler_, dsp, constraints_, false);
  SparsityTools::distribute_sparsity_pattern(dsp, owned_, comm_, relevant_);
  phase("matrix reinit");
  matrix_.reinit(owned_, owned_, dsp, comm_);
  phase(nullptr);
}

/// The supports must hold every rigid body motion: translations and rotations, evaluated at the
/// vertices of the supported faces, must not vanish on all constrained components together.
template <int dim>
void ElasticProblem<dim>::check_rigid_motion() const {
  const int n_modes = dim == 2 ? 3 : 6;
  std::vector<double> gram(n_modes * n_modes, 0.0);
  for_each_boundary_face([&](const auto& cell, unsigned f, types::boundary_id id) {
    for (std::size_t s = 0; s < problem_.supports.size(); ++s) {
      if (!carries(id, support_group_[s])) continue;
      for (unsigned v = 0; v < cell->face(f)->n_vertices(); ++v) {
        double x[3];
        mode_frame_.coordinates(cell->face(f)->vertex(v), x);
        for (int c : constrained_components(problem_.supports[s])) {
          std::vector<double> row(n_modes, 0.0);
          set_rigid_body_modes(dim, x, unsigned(c), 0, 1, row);
          for (int i = 0; i < n_modes; ++i)
            for (int j = 0; j < n_modes; ++j) gram[i * n_modes + j] += row[i] * row[j];
        }
      }
    }
  });
  Utilities::MPI::sum(gram, comm_, gram);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Eigen::Map<const Eigen::MatrixXd>(gram.data(), n_modes, n_modes));
  const Eigen::VectorXd& values = eigen.eigenvalues();
  const Eigen::MatrixXd& vectors = eigen.eigenvectors();
  const double top = std::max(values.maxCoeff(), 0.0);
  const char* names2[3] = {"translation along x", "translation along y", "rotation about z"};
  const char* names3[6] = {"translation along x", "translation along y", "translation along z",
                           "rotation about x",    "rotation about y",    "rotation about z"};
  for (int k = 0; k < n_modes; ++k)
    if (!(values[k] > 1e-10 * top) || top == 0) {
      int dominant = 0;
      for (int i = 0; i < n_modes; ++i)
        if (std::abs(vectors(i, k)) > std::abs(vectors(dominant, k))) dominant = i;
      throw Error(problem_.name + ": the supports leave the body free to move rigidly (" +
                  (dim == 2 ? names2[dominant] : names3[dominant]) +
                  "): no unique solution; add a rigid group or rollers that hold it");
    }
}

template <int dim>
void ElasticProblem<dim>::cell_system(const typename DoFHandler<dim>::active_cell_iterator& cell,
                                      FEValues<dim>& fe_values, FEFaceValues<dim>& fe_face_values,
                                      FullMatrix<double>& cell_matrix, Vector<double>& cell_rhs,
                                      bool with_matrix) {
  const unsigned n = fe_->n_dofs_per_cell(), nq = fe_values.n_quadrature_points;
  cell_matrix = 0;
  cell_rhs = 0;
  fe_values.reinit(cell);
  std::vector<Tensor<1, dim>> grads(n);
  std::vector<unsigned> comp(n);
  for (unsigned i = 0; i < n; ++i) comp[i] = fe_->system_to_component_index(i).first;
  const bool body = has_body_force();
  for (unsigned q = 0; q < nq; ++q) {
    const double JxW = fe_values.JxW(q);
    for (unsigned i = 0; i < n && with_matrix; ++i) grads[i] = fe_values.shape_grad(i, q);
    for (unsigned i = 0; i < n && with_matrix; ++i) {
      const unsigned ci = comp[i];
      const Tensor<1, dim>& gi = grads[i];
      for (unsigned j = 0; j <= i; ++j) {
        const unsigned cj = comp[j];
        const Tensor<1, dim>& gj = grads[j];
        cell_matrix(i, j) += elastic_entry<dim>(gi, gj, ci, cj, lambda_, mu_) * JxW;
      }
    }
    if (body) {
      double b[3] = {problem_.body_force[0], problem_.body_force[1], problem_.body_force[2]};
      if (problem_.body_force_function) {
        double extra[3] = {0, 0, 0};
        problem_.body_force_function(plain_point(fe_values.quadrature_point(q)).data(), extra);
        for (int a = 0; a < 3; ++a) b[a] += extra[a];
      }
      for (unsigned i = 0; i < n; ++i) cell_rhs(i) += fe_values.shape_value(i, q) * b[comp[i]] * JxW;
    }
  }
  for (unsigned i = 0; i < n; ++i)
    for (unsigned j = i + 1; j < n; ++j) cell_matrix(i, j) = cell_matrix(j, i);

  if (!cell->at_boundary() || traction_group_.empty()) return;
  for (unsigned f = 0; f < cell->n_faces(); ++f) {
    if (!cell->face(f)->at_boundary()) continue;
    const auto id = cell->face(f)->boundary_id();
    bool reinit = false;
    for (std::size_t t = 0; t < traction_group_.size(); ++t) {
      if (!carries(id, traction_group_[t])) continue;
      if (!reinit) fe_face_values.reinit(cell, f);
      reinit = true;
      const auto& traction = problem_.tractions[t];
      for (unsigned q = 0; q < fe_face_values.n_quadrature_points; ++q) {
        Tensor<1, dim> tq = uniform_traction_[t];
        if (traction.traction) {
          double v[3] = {0, 0, 0};
          traction.traction(plain_point(fe_face_values.quadrature_point(q)).data(), v);
          for (int a = 0; a < dim; ++a) tq[a] = v[a];
        }
        const double JxW = fe_face_values.JxW(q);
        for (unsigned i = 0; i < n; ++i) cell_rhs(i) += fe_face_values.shape_value(i, q) * tq[comp[i]] * JxW;
      }
    }
  }
}

template <int dim>
void ElasticProblem<dim>::assemble_system() {
  FEValues<dim> fe_values(*mapping_, *fe_, *quadrature_,
                          update_values | update_gradients | update_quadrature_points | update_JxW_values);
  FEFaceValues<dim> fe_face_values(*mapping_, *fe_, *face_quadrature_,
                                   update_values | update_quadrature_points | update_JxW_values);

  // Uniform tractions: total force over the group's area (times the thickness in 2D).
  std::vector<double> area(traction_group_.size(), 0.0);
  for_each_boundary_face([&](const auto& cell, unsigned f, types::boundary_id id) {
    bool reinit = false;
    for (std::size_t t = 0; t < traction_group_.size(); ++t)
      if (carries(id, traction_group_[t])) {
        if (!reinit) fe_face_values.reinit(cell, f);
        reinit = true;
        for (unsigned q = 0; q < fe_face_values.n_quadrature_points; ++q) area[t] += fe_face_values.JxW(q);
      }
  });
  Utilities::MPI::sum(area, comm_, area);
  uniform_traction_.assign(traction_group_.size(), Tensor<1, dim>());
  for (std::size_t t = 0; t < traction_group_.size(); ++t)
    for (int a = 0; a < dim; ++a) uniform_traction_[t][a] = problem_.tractions[t].force[a] / (area[t] * thickness_);

  const unsigned n = fe_->n_dofs_per_cell();
  FullMatrix<double> cell_matrix(n, n);
  Vector<double> cell_rhs(n);
  std::vector<types::global_dof_index> dofs(n);
  std::array<double, 3> applied{};
  const bool body = has_body_force();
  for (const auto& cell : dof_handler_.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    cell->get_dof_indices(dofs);
    if (!use_mg_) {
      cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs);
      constraints_.distribute_local_to_global(cell_matrix, cell_rhs, dofs, matrix_, rhs_);
    } else {
      // Right-hand side only; the element matrix where it moves inhomogeneous constraints over.
      bool inhomogeneous = false;
      for (auto d : dofs) inhomogeneous = inhomogeneous || constraints_.is_inhomogeneously_constrained(d);
      if (!inhomogeneous && !body && (!cell->at_boundary() || traction_group_.empty())) continue;
      cell_system(cell, fe_values, fe_face_values, cell_matrix, cell_rhs, inhomogeneous);
      constraints_.distribute_local_to_global(cell_rhs, dofs, rhs_, cell_matrix);
    }
    for (unsigned i = 0; i < n; ++i) applied[fe_->system_to_component_index(i).first] += cell_rhs(i);
  }

  // Point forces at the nearest vertex: every rank proposes its nearest vertex, all agree on the
  // closest (ties by coordinates), the owners of its DoFs add the force.
  point_loads_.clear();
  for (const auto& pf : problem_.point_forces) {
    Point<dim> target;
    for (int a = 0; a < dim; ++a) target[a] = pf.point[a];
    std::array<double, 4> best{1e308, 0, 0, 0};
    for (const auto& cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned v = 0; v < cell->n_vertices(); ++v) {
          const double d = cell->vertex(v).distance(target);
          std::array<double, 4> cand{d, 0, 0, 0};
          for (int a = 0; a < dim; ++a) cand[1 + a] = cell->vertex(v)[a];
          if (cand < best) best = cand;
        }
    const auto all = Utilities::MPI::all_gather(comm_, best);
    best = *std::min_element(all.begin(), all.end());
    std::set<types::global_dof_index> done;
    for (const auto& cell : dof_handler_.active_cell_iterators())
      if (cell->is_locally_owned())
        for (unsigned v = 0; v < cell->n_vertices(); ++v) {
          bool same = true;
          for (int a = 0; a < dim; ++a) same = same && cell->vertex(v)[a] == best[1 + a];
          if (!same) continue;
          for (int c = 0; c < dim; ++c) {
            const auto dof = cell->vertex_dof_index(v, c);
            if (!owned_.is_element(dof) || !done.insert(dof).second) continue;
            const double value = pf.force[c] / thickness_;
            point_loads_.emplace_back(dof, value);
            applied[c] += value;
            if (!constraints_.is_constrained(dof)) rhs_(dof) += value;
          }
        }
  }
  if (!use_mg_) matrix_.compress(VectorOperation::add);
  rhs_.compress(VectorOperation::add);
  for (int a = 0; a < 3; ++a) applied_[a] = Utilities::MPI::sum(applied[a], comm_) * thickness_;
}

template <int dim>
void ElasticProblem<dim>::solve() {
  const auto& o = problem_.options;
  const double rhs_norm = rhs_.l2_norm();
  if (rhs_norm == 0) {
    solution_ = 0;
    result_.solver = "none (no load)";
  } else if (use_mg_) {
    MgSettings s;
    s.lambda = lambda_;
    s.mu = mu_;
    s.tolerance = o.tolerance;
    s.max_iterations = o.max_iterations;
    s.direct_limit = o.direct_limit;
    s.mode_frame = mode_frame_;
    MgBoundaries boundaries;
    for (std::size_t k = 0; k < problem_.supports.size(); ++k) {
      ComponentMask mask(dim, false);
      for (int c : constrained_components(problem_.supports[k])) mask.set(c, true);
      std::set<types::boundary_id> ids;
      for (types::boundary_id id = 1; id < groups_of_id_.size(); ++id)
        if (carries(id, support_group_[k])) ids.insert(id);
      if (!ids.empty()) boundaries.emplace_back(ids, mask);
    }
    s.coarser_share = o.coarser_share;
    // The coarse mesh's own solution from the hierarchy (FemOptions::coarser_level): a mesh refined
    // once, and constraints that are zero (a prescribed displacement would need its own lift).
    const bool coarser = o.coarser_level && tria_->n_global_levels() == 2 &&
                         std::none_of(problem_.supports.begin(), problem_.supports.end(),
                                      [](const Support& p) { return p.kind == SupportKind::Displacement; });
    if (coarser) coarser_.reinit(owned_, comm_);
    MgOutcome outcome;
    try {
      outcome = solve_mg(*mapping_, dof_handler_, constraints_, boundaries, rhs_, solution_, s,
                         [&](const char* what) { phase(what); }, coarser ? &coarser_ : nullptr);
    } catch (const SolverControl::NoConvergence& e) {
      require_finite(std::isfinite(e.last_residual), "CG residual");
      throw Error(no_convergence(problem_, "geometric multigrid", e));
    }
    result_.solver = outcome.solver;
    result_.iterations = outcome.iterations;
    profile_out_ << "fem-profile: element matrices stored per level:";
    for (std::size_t n : outcome.matrices_per_level) profile_out_ << ' ' << n;
    profile_out_ << std::endl;
    constraints_.distribute(solution_);
    result_.residual = outcome.residual;
    ghosted_ = solution_;
    if (coarser) {
      constraints_.distribute(coarser_);
      coarser_outcome_ = outcome;
    }
    return;
  } else if (direct_) {
    phase("factorisation");
    const DirectSolver direct(matrix_);
    phase("direct solve");
    direct.solve(solution_, rhs_);
    phase(nullptr);
    result_.solver = "direct (" + direct.name() + ")";
    result_.iterations = 0;
  } else {
    // ML smoothed aggregation with the rigid body modes as near-null space.
    phase("rigid body modes");
    std::vector<double> modes = rigid_body_modes<dim>(
        *mapping_, *fe_, dof_handler_.active_cell_iterators(),
        [](const auto& cell, std::vector<types::global_dof_index>& dofs) {
          if (!cell->is_locally_owned()) return false;
          cell->get_dof_indices(dofs);
          return true;
        },
        owned_, mode_frame_);
    phase("AMG setup");
    TrilinosWrappers::PreconditionAMG amg;
    initialize_elasticity_ml(amg, matrix_, dim, degree_, modes);
    phase("CG");
    SolverControl control(o.max_iterations, o.tolerance * rhs_norm, false, false);
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try {
      cg.solve(matrix_, solution_, rhs_, amg);
    } catch (const SolverControl::NoConvergence& e) {
      require_finite(std::isfinite(e.last_residual), "CG residual");
      throw Error(no_convergence(problem_, "AMG", e));
    }
    phase(nullptr);
    result_.solver = "cg+amg (ML)";
    result_.iterations = int(control.last_step());
  }
  constraints_.distribute(solution_);
  TrilinosWrappers::MPI::Vector residual(owned_, comm_);
  matrix_.vmult(residual, solution_);
  residual -= rhs_;
  result_.residual = rhs_norm == 0 ? 0.0 : residual.l2_norm() / rhs_norm;
  ghosted_ = solution_;
}

// The members defined here, for both dimensions (elastic_problem.cc instantiates the class).
template void ElasticProblem<2>::make_grid();
template void ElasticProblem<3>::make_grid();
template void ElasticProblem<2>::choose_solver();
template void ElasticProblem<3>::choose_solver();
template void ElasticProblem<2>::sort_dofs_by_position();
template void ElasticProblem<3>::sort_dofs_by_position();
template void ElasticProblem<2>::setup_system();
template void ElasticProblem<3>::setup_system();
template void ElasticProblem<2>::check_rigid_motion() const;
template void ElasticProblem<3>::check_rigid_motion() const;
template void ElasticProblem<2>::assemble_system();
template void ElasticProblem<3>::assemble_system();
template void ElasticProblem<2>::solve();
template void ElasticProblem<3>::solve();
template void ElasticProblem<2>::cell_system(const DoFHandler<2>::active_cell_iterator&, FEValues<2>&, FEFaceValues<2>&,
                                             FullMatrix<double>&, Vector<double>&, bool);
template void ElasticProblem<3>::cell_system(const DoFHandler<3>::active_cell_iterator&, FEValues<3>&, FEFaceValues<3>&,
                                             FullMatrix<double>&, Vector<double>&, bool);
template std::vector<int> ElasticProblem<2>::constrained_components(const Support&) const;
template std::vector<int> ElasticProblem<3>::constrained_components(const Support&) const;

}  // namespace fem_reference
