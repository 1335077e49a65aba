// Matrix-free geometric multigrid for the FEM reference (see mg_solver.h). Its own translation unit
// (about 20-30 s to compile, as each of the problem's two) so that they compile in parallel;
// instantiated for dim 2, 3 and degree 1, 2.
#include "mg/mg_solver.h"

#include "mg/cell_matrix_operator.h"

#include "amg/amg.h"
#include "direct/direct_solver.h"
#include "elasticity.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/lac/precondition.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/matrix_free/fe_evaluation.h>
#include <deal.II/matrix_free/matrix_free.h>
#include <deal.II/matrix_free/operators.h>
#include <deal.II/matrix_free/tools.h>
#include <deal.II/multigrid/mg_coarse.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>
#include <deal.II/multigrid/mg_matrix.h>
#include <deal.II/multigrid/mg_smoother.h>
#include <deal.II/multigrid/mg_tools.h>
#include <deal.II/multigrid/mg_transfer_matrix_free.h>
#include <deal.II/multigrid/multigrid.h>

#include <cstdlib>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

namespace fem_reference {

using namespace dealii;

namespace {

/// (lambda div u div v + mu (grad u + grad u^T) : grad v), matrix-free (deal.II's sum
/// factorisation): here only to compute the coarse level's matrix for the direct solver or ML.
template <int dim, int degree, typename number>
class ElasticOperator : public MatrixFreeOperators::Base<dim, LinearAlgebra::distributed::Vector<number>> {
 public:
  using VectorType = LinearAlgebra::distributed::Vector<number>;
  using Eval = FEEvaluation<dim, degree, degree + 1, dim, number>;

  void set_coefficients(double lambda, double mu) {
    lambda_ = number(lambda);
    mu_ = number(mu);
  }

  void compute_diagonal() override {
    this->inverse_diagonal_entries.reset(new DiagonalMatrix<VectorType>());
    VectorType& d = this->inverse_diagonal_entries->get_vector();
    this->data->initialize_dof_vector(d);
    MatrixFreeTools::compute_diagonal(*this->data, d, &ElasticOperator::cell_operation, this);
    this->set_constrained_entries_to_one(d);
    for (unsigned i = 0; i < d.locally_owned_size(); ++i)
      d.local_element(i) = d.local_element(i) > 0 ? number(1) / d.local_element(i) : number(1);
  }

  /// The element operator at the quadrature points of one batch of cells.
  void cell_operation(Eval& phi) const {
    phi.evaluate(EvaluationFlags::gradients);
    for (unsigned q = 0; q < phi.n_q_points; ++q) {
      // sigma = 2 mu eps + lambda tr(eps) I (symmetric, so sigma : grad v = sigma : eps(v))
      SymmetricTensor<2, dim, VectorizedArray<number>> e = phi.get_symmetric_gradient(q);
      const VectorizedArray<number> tr = lambda_ * trace(e);
      e *= 2 * mu_;
      for (int a = 0; a < dim; ++a) e[a][a] += tr;
      phi.submit_symmetric_gradient(e, q);
    }
    phi.integrate(EvaluationFlags::gradients);
  }

 private:
  void apply_add(VectorType& dst, const VectorType& src) const override {
    this->data->cell_loop(&ElasticOperator::local_apply, this, dst, src);
  }
  void local_apply(const MatrixFree<dim, number>& data, VectorType& dst, const VectorType& src,
                   const std::pair<unsigned, unsigned>& range) const {
    Eval phi(data);
    for (unsigned cell = range.first; cell < range.second; ++cell) {
      phi.reinit(cell);
      phi.read_dof_values(src);
      cell_operation(phi);
      phi.distribute_local_to_global(dst);
    }
  }

  number lambda_ = 0, mu_ = 0;
};

/// The coarse level (level 0) of the hierarchy: inside the V-cycle (operator()) and on its own
/// (solve: the coarser level's solution). The boundary DoFs of the level stay zero.
class CoarseLevel : public MGCoarseGridBase<LinearAlgebra::distributed::Vector<float>> {
 public:
  using LevelVector = LinearAlgebra::distributed::Vector<float>;
  using Vector = LinearAlgebra::distributed::Vector<double>;
  /// The level's own problem K0 x = b to `tolerance` (relative residual). Returns the CG
  /// iterations (0 for a direct solve) and the relative residual.
  virtual std::pair<int, double> solve(Vector& x, const Vector& b, double tolerance, int max_iterations) const = 0;
};

/// Level 0 assembled: the direct solver on its matrix (or one ML cycle when it is large).
template <int dim, int degree>
class CoarseSolver : public CoarseLevel {
 public:
  CoarseSolver(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const MGConstrainedDoFs& mg_constrained,
               const MgSettings& s, std::string& name)
  {
    const MPI_Comm comm = dof.get_communicator();
    IndexSet relevant;
    DoFTools::extract_locally_relevant_level_dofs(dof, 0, relevant);
    AffineConstraints<double> constraints;
    constraints.reinit(relevant);
    constraints.add_lines(mg_constrained.get_boundary_indices(0));
    constraints.close();
    boundary_ = mg_constrained.get_boundary_indices(0);

    typename MatrixFree<dim, double>::AdditionalData data;
    data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags = update_gradients | update_JxW_values;
    data.mg_level = 0;
    auto mf = std::make_shared<MatrixFree<dim, double>>();
    mf->reinit(mapping, dof, constraints, QGauss<1>(degree + 1), data);
    ElasticOperator<dim, degree, double> op;
    op.initialize(mf, mg_constrained, 0);
    op.set_coefficients(s.lambda, s.mu);

    DynamicSparsityPattern dsp(relevant);
    MGTools::make_sparsity_pattern(dof, dsp, 0);
    const IndexSet& owned = dof.locally_owned_mg_dofs(0);
    SparsityTools::distribute_sparsity_pattern(dsp, owned, comm, relevant);
    matrix_.reinit(owned, owned, dsp, comm);
    MatrixFreeTools::compute_matrix(*mf, constraints, matrix_, &ElasticOperator<dim, degree, double>::cell_operation,
                                    &op);
    mf->initialize_dof_vector(b_);
    x_.reinit(b_);

    if (coarse_direct_is_fast(double(dof.n_dofs(0)), dim, s.direct_limit)) {
      direct_ = std::make_unique<DirectSolver>(matrix_);
      name = direct_->name();
    } else {
      // ML with the rigid body modes of the coarse mesh as near-null space (as the "amg" solver).
      modes_ = rigid_body_modes<dim>(
          mapping, dof.get_fe(), dof.mg_cell_iterators_on_level(0),
          [](const auto& cell, std::vector<types::global_dof_index>& dofs) {
            if (!cell->is_locally_owned_on_level()) return false;
            cell->get_mg_dof_indices(dofs);
            return true;
          },
          dof.locally_owned_mg_dofs(0), s.mode_frame);
      amg_ = std::make_unique<TrilinosWrappers::PreconditionAMG>();
      initialize_elasticity_ml(*amg_, matrix_, dim, degree, modes_);
      name = "ML AMG cycle";
    }
  }

  /// The direct solver, or CG with the ML preconditioner.
  std::pair<int, double> solve(Vector& x, const Vector& b, double tolerance, int max_iterations) const override {
    for (unsigned i = 0; i < b_.locally_owned_size(); ++i) b_.local_element(i) = b.local_element(i);
    for (auto i : boundary_)
      if (b_.in_local_range(i)) b_(i) = 0;
    x_ = 0;
    int iterations = 0;
    if (direct_) {
      direct_->solve(x_, b_);
    } else {
      struct BoundaryZeroAmg {  // the ML cycle with the level's boundary DoFs held at zero
        const CoarseSolver* s;
        void vmult(LinearAlgebra::distributed::Vector<double>& dst, const LinearAlgebra::distributed::Vector<double>& src) const {
          s->amg_->vmult(dst, src);
          for (auto i : s->boundary_)
            if (dst.in_local_range(i)) dst(i) = 0;
        }
      };
      SolverControl control(max_iterations, tolerance * b_.l2_norm(), false, false);
      SolverCG<LinearAlgebra::distributed::Vector<double>> cg(control);
      cg.solve(matrix_, x_, b_, BoundaryZeroAmg{this});
      iterations = int(control.last_step());
    }
    LinearAlgebra::distributed::Vector<double> r(b_);
    matrix_.vmult(r, x_);
    r -= b_;
    const double b_norm = b_.l2_norm();
    for (unsigned i = 0; i < x.locally_owned_size(); ++i) x.local_element(i) = x_.local_element(i);
    return {iterations, b_norm == 0 ? 0.0 : r.l2_norm() / b_norm};
  }

  void operator()(const unsigned int, LevelVector& dst, const LevelVector& src) const override {
    for (unsigned i = 0; i < b_.locally_owned_size(); ++i) b_.local_element(i) = src.local_element(i);
    apply(x_, b_);
    for (unsigned i = 0; i < x_.locally_owned_size(); ++i) dst.local_element(i) = float(x_.local_element(i));
  }

  /// x = one direct solve or one ML cycle of b (b's boundary entries set to zero here, x's zero).
  void apply(Vector& x, Vector& b) const {
    for (auto i : boundary_)
      if (b.in_local_range(i)) b(i) = 0;
    if (direct_)
      direct_->solve(x, b);
    else
      amg_->vmult(x, b);
    for (auto i : boundary_)
      if (x.in_local_range(i)) x(i) = 0;
  }

  /// A vector of the level's layout (owned DoFs of level 0).
  void initialize_vector(Vector& v) const { v.reinit(b_); }

 private:
  TrilinosWrappers::SparseMatrix matrix_;
  std::unique_ptr<DirectSolver> direct_;
  std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_;
  IndexSet boundary_;
  std::vector<double> modes_;  // ML keeps a pointer
  mutable LinearAlgebra::distributed::Vector<double> b_, x_;
};

/// Level 0 of degree 2 without its matrix: a two-level p-multigrid under it. The level's operator
/// from stored element matrices (double), Chebyshev-Jacobi smoothing on it, and the same mesh in
/// Q1 (CoarseSolver<dim, 1>: the direct solver or one ML cycle on its assembled matrix) for the rest, reached by
/// interpolation (Q1 lies in Q2: P's column j is the Q1 shape function j at the Q2 nodes).
/// Inside the V-cycle one p-cycle; on its own CG preconditioned by it. ML on the assembled Q2 level
/// cost more than the solves it served (block3d: 11.7 s of set-up for 206,763 DoFs, 375 entries
/// per row; Q1 on the same mesh: 27,783 DoFs, 81 per row).
template <int dim>
class PCoarsenedSolver : public CoarseLevel {
 public:
  PCoarsenedSolver(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const MGConstrainedDoFs& mg_constrained,
                   const MgBoundaries& boundaries, const MgSettings& s, std::string& name)
      : linear_fe_(FE_Q<dim>(1), dim), linear_dof_(dof.get_triangulation()) {
    op_.build(mapping, dof, mg_constrained, 0, s.lambda, s.mu);
    boundary_ = mg_constrained.get_boundary_indices(0);
    linear_dof_.distribute_dofs(linear_fe_);
    linear_dof_.distribute_mg_dofs();
    linear_constrained_.initialize(linear_dof_);
    for (const auto& [ids, mask] : boundaries) linear_constrained_.make_zero_boundary_constraints(linear_dof_, ids, mask);
    std::string linear_name;
    linear_ = std::make_unique<CoarseSolver<dim, 1>>(mapping, linear_dof_, linear_constrained_, s, linear_name);
    build_interpolation(dof);

    typename Smoother::AdditionalData data;
    data.smoothing_range = 15.;
    data.degree = unsigned(s.smoother_degree);
    data.eig_cg_n_iterations = 12;
    data.preconditioner = op_.inverse_diagonal();
    smoother_.initialize(op_, data);
    op_.initialize_dof_vector(b_);
    x_.reinit(b_);
    r_.reinit(b_);
    e_.reinit(b_);
    linear_->initialize_vector(rc_);
    ec_.reinit(rc_);
    name = "p-multigrid to Q1 (Chebyshev " + std::to_string(s.smoother_degree) + ", Q1 " + linear_name + ")";
  }

  void operator()(const unsigned int, LevelVector& dst, const LevelVector& src) const override {
    for (unsigned i = 0; i < b_.locally_owned_size(); ++i) b_.local_element(i) = src.local_element(i);
    cycle(x_, b_);
    for (unsigned i = 0; i < x_.locally_owned_size(); ++i) dst.local_element(i) = float(x_.local_element(i));
  }

  /// CG on the level's operator, preconditioned by the p-cycle.
  std::pair<int, double> solve(Vector& x, const Vector& b, double tolerance, int max_iterations) const override {
    for (unsigned i = 0; i < b_.locally_owned_size(); ++i) b_.local_element(i) = b.local_element(i);
    zero_boundary(b_);
    Vector solution(b_);
    solution = 0;
    struct Cycle {
      const PCoarsenedSolver* s;
      void vmult(Vector& dst, const Vector& src) const { s->cycle(dst, src); }
    };
    SolverControl control(max_iterations, tolerance * b_.l2_norm(), false, false);
    SolverCG<Vector> cg(control);
    cg.solve(op_, solution, b_, Cycle{this});
    op_.vmult(r_, solution);
    r_ -= b_;
    const double b_norm = b_.l2_norm();
    for (unsigned i = 0; i < x.locally_owned_size(); ++i) x.local_element(i) = solution.local_element(i);
    return {int(control.last_step()), b_norm == 0 ? 0.0 : r_.l2_norm() / b_norm};
  }

 private:
  using Operator = CellMatrixOperator<dim, double>;
  using Smoother = PreconditionChebyshev<Operator, Vector>;

  void zero_boundary(Vector& v) const {
    for (auto i : boundary_)
      if (v.in_local_range(i)) v(i) = 0;
  }

  /// P: rows the owned Q2 DoFs of level 0, each written once from one cell that holds it (a Q1
  /// function's value at a node is the same from every cell around it).
  void build_interpolation(const DoFHandler<dim>& dof) {
    const FiniteElement<dim>& fe = dof.get_fe();
    FullMatrix<double> local(fe.n_dofs_per_cell(), linear_fe_.n_dofs_per_cell());
    fe.get_interpolation_matrix(linear_fe_, local);
    const IndexSet& owned = dof.locally_owned_mg_dofs(0);
    const IndexSet& linear_owned = linear_dof_.locally_owned_mg_dofs(0);
    IndexSet relevant;
    DoFTools::extract_locally_relevant_level_dofs(dof, 0, relevant);
    std::vector<types::global_dof_index> rows(fe.n_dofs_per_cell()), columns(linear_fe_.n_dofs_per_cell());
    std::vector<bool> written(owned.n_elements(), false);
    DynamicSparsityPattern dsp(dof.n_dofs(0), linear_dof_.n_dofs(0), relevant);
    std::vector<std::pair<types::global_dof_index, std::pair<types::global_dof_index, double>>> entries;
    auto linear_cell = linear_dof_.begin_mg(0);
    for (auto cell = dof.begin_mg(0); cell != dof.end_mg(0); ++cell, ++linear_cell) {
      if (!cell->is_locally_owned_on_level()) continue;
      cell->get_mg_dof_indices(rows);
      linear_cell->get_mg_dof_indices(columns);
      for (unsigned i = 0; i < rows.size(); ++i) {
        if (!owned.is_element(rows[i]) || written[owned.index_within_set(rows[i])]) continue;
        written[owned.index_within_set(rows[i])] = true;
        for (unsigned j = 0; j < columns.size(); ++j)
          if (std::abs(local(i, j)) > 1e-12) {
            dsp.add(rows[i], columns[j]);
            entries.push_back({rows[i], {columns[j], local(i, j)}});
          }
      }
    }
    interpolation_.reinit(owned, linear_owned, dsp, dof.get_communicator());
    for (const auto& [row, entry] : entries) interpolation_.set(row, entry.first, entry.second);
    interpolation_.compress(VectorOperation::insert);
  }

  /// x = one p-cycle of b: smooth, the Q1 correction of the residual, smooth again (symmetric).
  void cycle(Vector& x, const Vector& b) const {
    smoother_.vmult(x, b);
    residual(x, b);
    interpolation_.Tvmult(rc_, r_);
    linear_->apply(ec_, rc_);
    interpolation_.vmult(e_, ec_);
    x += e_;
    residual(x, b);
    smoother_.vmult(e_, r_);
    x += e_;
    zero_boundary(x);
  }

  /// r_ = b - K0 x, zero on the boundary.
  void residual(const Vector& x, const Vector& b) const {
    op_.vmult(r_, x);
    r_.sadd(-1., 1., b);
    zero_boundary(r_);
  }

  Operator op_;
  Smoother smoother_;
  IndexSet boundary_;
  FESystem<dim> linear_fe_;
  DoFHandler<dim> linear_dof_;
  MGConstrainedDoFs linear_constrained_;
  std::unique_ptr<CoarseSolver<dim, 1>> linear_;
  TrilinosWrappers::SparseMatrix interpolation_;
  mutable Vector b_, x_, r_, e_, rc_, ec_;
};

/// The homogeneous version of the supports' constraints (zero lines only; a globally refined mesh
/// has no hanging nodes) and the constrained DoFs.
template <int dim>
void homogeneous_constraints(const DoFHandler<dim>& dof, const AffineConstraints<double>& constraints,
                             AffineConstraints<double>& homogeneous, IndexSet& constrained) {
  IndexSet relevant;
  DoFTools::extract_locally_relevant_dofs(dof, relevant);
  homogeneous.reinit(relevant);
  for (const auto& line : constraints.get_lines()) {
    AssertThrow(line.entries.empty(), ExcMessage("the multigrid solver takes supports only, no hanging nodes"));
    homogeneous.add_line(line.index);
    constrained.add_index(line.index);
  }
  homogeneous.close();
  constrained.compress();
}

/// Chebyshev smoothing on every level. The finest level's eigenvalue bound is the next coarser
/// one's (the Lanczos estimate times 1.2, computed here rather than in the first V-cycle): the
/// largest eigenvalue of diag(K)^-1 K belongs to the element-scale modes, the same on every level
/// of a uniform refinement, and its 12 CG steps on the finest level cost as much as a V-cycle's
/// smoothing there.
template <class LevelOperator, class LevelVector, class Smoother>
void chebyshev_smoother(const MGLevelObject<LevelOperator>& levels, int smoother_degree,
                        mg::SmootherRelaxation<Smoother, LevelVector>& smoother) {
  const unsigned n_levels = levels.max_level() + 1;
  MGLevelObject<typename Smoother::AdditionalData> smoother_data(0, n_levels - 1);
  for (unsigned level = 0; level < n_levels; ++level) {
    smoother_data[level].smoothing_range = 15.;
    smoother_data[level].degree = unsigned(smoother_degree);
    smoother_data[level].eig_cg_n_iterations = 12;
    smoother_data[level].preconditioner = levels[level].inverse_diagonal();
  }
  smoother.initialize(levels, smoother_data);
  if (n_levels > 2) {
    LevelVector v;
    levels[n_levels - 2].initialize_dof_vector(v);
    v = 1.;
    const auto info = smoother[n_levels - 2].estimate_eigenvalues(v);
    smoother_data[n_levels - 1].eig_cg_n_iterations = 0;
    smoother_data[n_levels - 1].max_eigenvalue = info.max_eigenvalue_estimate;
    smoother[n_levels - 1].initialize(levels[n_levels - 1], smoother_data[n_levels - 1]);
  }
}

/// ||K x - b|| with the constrained entries left out.
template <class Operator, class VectorType>
double residual_norm(const Operator& system, const AffineConstraints<double>& homogeneous, const VectorType& x,
                     const VectorType& b) {
  VectorType r;
  r.reinit(x);
  system.vmult(r, x);
  r -= b;
  homogeneous.set_zero(r);
  return r.l2_norm();
}

template <int dim, int degree>
MgOutcome solve_mg_degree(const Mapping<dim>& mapping, DoFHandler<dim>& dof, const AffineConstraints<double>& constraints,
                          const MgBoundaries& boundaries, const TrilinosWrappers::MPI::Vector& rhs,
                          TrilinosWrappers::MPI::Vector& solution, const MgSettings& s,
                          const std::function<void(const char*)>& profile, TrilinosWrappers::MPI::Vector* coarser) {
  using SystemOperator = CellMatrixOperator<dim, double>;
  using LevelOperator = CellMatrixOperator<dim, float>;
  using VectorType = LinearAlgebra::distributed::Vector<double>;
  using LevelVector = LinearAlgebra::distributed::Vector<float>;

  profile("active operator");
  // The active mesh's operator, on the homogeneous version of the constraints: zero lines only (the
  // supports; a globally refined mesh has no hanging nodes).
  AffineConstraints<double> homogeneous;
  IndexSet constrained(dof.n_dofs());
  homogeneous_constraints(dof, constraints, homogeneous, constrained);
  SystemOperator system;
  system.build(mapping, dof, constrained, s.lambda, s.mu);

  // The levels.
  profile("level DoFs");
  dof.distribute_mg_dofs();
  MGConstrainedDoFs mg_constrained;
  mg_constrained.initialize(dof);
  for (const auto& [ids, mask] : boundaries) mg_constrained.make_zero_boundary_constraints(dof, ids, mask);
  const unsigned n_levels = dof.get_triangulation().n_global_levels();
  profile("level operators");
  MGLevelObject<LevelOperator> levels(0, n_levels - 1);
  std::vector<std::shared_ptr<const Utilities::MPI::Partitioner>> partitioners(n_levels);
  for (unsigned level = 0; level < n_levels; ++level) {
    levels[level].build(mapping, dof, mg_constrained, level, s.lambda, s.mu);
    partitioners[level] = levels[level].partitioner();
  }
  profile("transfer");
  MGTransferMatrixFree<dim, float> transfer(mg_constrained);
  transfer.build(dof, partitioners);

  profile("smoothers");
  using Smoother = PreconditionChebyshev<LevelOperator, LevelVector>;
  mg::SmootherRelaxation<Smoother, LevelVector> smoother;
  chebyshev_smoother(levels, s.smoother_degree, smoother);
  profile("coarse solver");
  std::string coarse_name;
  std::unique_ptr<CoarseLevel> coarse_level;
  // A Q2 level is factorised where a whole problem on a square would be, else p-coarsened.
  if (degree == 2 && !direct_is_fast(double(dof.n_dofs(0)), 1.0, s.direct_limit))
    coarse_level = std::make_unique<PCoarsenedSolver<dim>>(mapping, dof, mg_constrained, boundaries, s, coarse_name);
  else
    coarse_level = std::make_unique<CoarseSolver<dim, degree>>(mapping, dof, mg_constrained, s, coarse_name);
  const CoarseLevel& coarse = *coarse_level;
  mg::Matrix<LevelVector> mg_matrix(levels);
  Multigrid<LevelVector> mg(mg_matrix, coarse, transfer, smoother, smoother);
  PreconditionMG<dim, LevelVector, MGTransferMatrixFree<dim, float>> preconditioner(dof, mg, transfer);

  VectorType b, x;
  system.initialize_dof_vector(b);
  system.initialize_dof_vector(x);
  for (auto i : b.get_partitioner()->locally_owned_range()) b(i) = rhs(i);
  homogeneous.set_zero(b);
  const double b_norm = rhs.l2_norm();
  MgOutcome out;
  double stop = s.tolerance * b_norm;
  if (coarser) {  // the coarse mesh's own solution, from this hierarchy, and the fine CG's start
    profile("coarser level");
    AssertThrow(n_levels == 2, ExcMessage("the coarser solution needs a mesh refined once"));
    MGTransferMatrixFree<dim, double> embedding(mg_constrained);  // in double: the solution itself moves
    embedding.build(dof);
    MGLevelObject<VectorType> level(0, n_levels - 1);
    embedding.copy_to_mg(dof, level, b);
    level[0] = 0;
    embedding.restrict_and_add(1, level[0], level[1]);
    VectorType coarse_solution(level[0]);
    std::tie(out.coarser_iterations, out.coarser_residual) =
        coarse.solve(coarse_solution, level[0], s.tolerance, s.max_iterations);
    out.coarser_dofs = dof.n_dofs(0);
    embedding.prolongate(1, level[1], coarse_solution);
    embedding.copy_from_mg(dof, x, level);
    homogeneous.set_zero(x);
    for (auto i : x.get_partitioner()->locally_owned_range()) (*coarser)(i) = x(i);
    coarser->compress(VectorOperation::insert);
    const double start = residual_norm(system, homogeneous, x, b);
    out.coarser_start_residual = b_norm == 0 ? 0.0 : start / b_norm;
    stop = std::max(stop, s.coarser_share * start);
  }
  profile("CG");
  SolverControl control(s.max_iterations, stop, false, false);
  SolverCG<VectorType> cg(control);
  cg.solve(system, x, b, preconditioner);
  profile(nullptr);

  out.iterations = int(control.last_step());
  for (unsigned level = 0; level < n_levels; ++level) out.matrices_per_level.push_back(levels[level].shapes());
  const double residual = residual_norm(system, homogeneous, x, b);
  out.residual = b_norm == 0 ? 0.0 : residual / b_norm;
  for (auto i : x.get_partitioner()->locally_owned_range()) solution(i) = x(i);
  solution.compress(VectorOperation::insert);
  out.solver = "cg+gmg (matrix-free, " + std::to_string(n_levels) + " levels, Chebyshev " +
               std::to_string(s.smoother_degree) + ", coarse " + coarse_name + ")";
  out.coarse_solver = coarse_name;
  return out;
}

}  // namespace

template <int dim>
MgOutcome solve_mg(const Mapping<dim>& mapping, DoFHandler<dim>& dof, const AffineConstraints<double>& constraints,
                   const MgBoundaries& boundaries, const TrilinosWrappers::MPI::Vector& rhs,
                   TrilinosWrappers::MPI::Vector& solution, const MgSettings& s,
                   const std::function<void(const char*)>& profile, TrilinosWrappers::MPI::Vector* coarser) {
  if (dof.get_fe().degree == 1)
    return solve_mg_degree<dim, 1>(mapping, dof, constraints, boundaries, rhs, solution, s, profile, coarser);
  return solve_mg_degree<dim, 2>(mapping, dof, constraints, boundaries, rhs, solution, s, profile, coarser);
}

template MgOutcome solve_mg<2>(const Mapping<2>&, DoFHandler<2>&, const AffineConstraints<double>&, const MgBoundaries&,
                               const TrilinosWrappers::MPI::Vector&, TrilinosWrappers::MPI::Vector&, const MgSettings&,
                               const std::function<void(const char*)>&, TrilinosWrappers::MPI::Vector*);
template MgOutcome solve_mg<3>(const Mapping<3>&, DoFHandler<3>&, const AffineConstraints<double>&, const MgBoundaries&,
                               const TrilinosWrappers::MPI::Vector&, TrilinosWrappers::MPI::Vector&, const MgSettings&,
                               const std::function<void(const char*)>&, TrilinosWrappers::MPI::Vector*);

}  // namespace fem_reference
