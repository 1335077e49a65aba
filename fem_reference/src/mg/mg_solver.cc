// Matrix-free geometric multigrid for the FEM reference (see mg_solver.h). Its own translation unit
// (about 20-30 s to compile, as each of the problem's two) so that they compile in parallel;
// instantiated for dim 2, 3 and degree 1, 2.
#include "mg/mg_solver.h"

#include "amg/amg.h"
#include "elasticity.h"

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
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

namespace fem_reference {

using namespace dealii;

namespace {

/// (lambda div u div v + mu (grad u + grad u^T) : grad v), matrix-free, on the active mesh (level
/// = invalid) or on one multigrid level.
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

/// A multigrid level operator from stored element matrices (single precision), applied cell by
/// cell: gather, small dense product, scatter. Deal.II's MatrixFree runs without SIMD here
/// (Debian's deal.II is configured with vectorization width 0), where sum factorisation on Q1/Q2
/// cells is about three times slower than this. Cells of the same shape (to single precision)
/// share one matrix, so a structured mesh stores a handful; boundary DoFs of the level get
/// identity rows and columns.
template <int dim>
class CellMatrixOperator : public Subscriptor {
 public:
  using VectorType = LinearAlgebra::distributed::Vector<float>;

  void build(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const MGConstrainedDoFs& mg_constrained,
             unsigned level, double lambda, double mu) {
    const auto& fe = dof.get_fe();
    n_ = fe.n_dofs_per_cell();
    IndexSet relevant;
    DoFTools::extract_locally_relevant_level_dofs(dof, level, relevant);
    partitioner_ = std::make_shared<Utilities::MPI::Partitioner>(dof.locally_owned_mg_dofs(level), relevant,
                                                                 dof.get_communicator());
    const IndexSet& boundary = mg_constrained.get_boundary_indices(level);
    QGauss<dim> quadrature(fe.degree + 1);
    FEValues<dim> fe_values(mapping, fe, quadrature, update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> dofs(n_);
    std::vector<unsigned> comp(n_);
    for (unsigned i = 0; i < n_; ++i) comp[i] = fe.system_to_component_index(i).first;
    std::map<std::vector<float>, unsigned> shapes;  // shape (vertices - vertex 0) and boundary pattern
    std::vector<float> key;
    std::vector<Tensor<1, dim>> grads(n_);
    for (const auto& cell : dof.mg_cell_iterators_on_level(level)) {
      if (!cell->is_locally_owned_on_level()) continue;
      cell->get_mg_dof_indices(dofs);
      // Shape to about 1e-7 of the cell size (rounding noise of the mesh coordinates removed).
      key.clear();
      double scale = 0;
      for (unsigned v = 1; v < cell->n_vertices(); ++v)
        for (int a = 0; a < dim; ++a) scale = std::max(scale, std::abs(cell->vertex(v)[a] - cell->vertex(0)[a]));
      key.push_back(float(scale));
      for (unsigned v = 1; v < cell->n_vertices(); ++v)
        for (int a = 0; a < dim; ++a)
          key.push_back(float(std::round((cell->vertex(v)[a] - cell->vertex(0)[a]) / scale * 4194304.0)));
      for (unsigned i = 0; i < n_; ++i) key.push_back(boundary.is_element(dofs[i]) ? 1.f : 0.f);
      for (auto d : dofs) cell_dofs_.push_back(partitioner_->global_to_local(d));
      auto [it, added] = shapes.emplace(key, unsigned(shapes.size()));
      cell_matrix_.push_back(it->second);
      if (!added) continue;
      fe_values.reinit(cell);
      std::vector<double> m(n_ * n_, 0.0);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        const double JxW = fe_values.JxW(q);
        for (unsigned i = 0; i < n_; ++i) grads[i] = fe_values.shape_grad(i, q);
        for (unsigned i = 0; i < n_; ++i)
          for (unsigned j = 0; j < n_; ++j) {
            const unsigned ci = comp[i], cj = comp[j];
            m[i * n_ + j] += elastic_entry<dim>(grads[i], grads[j], ci, cj, lambda, mu) * JxW;
          }
      }
      for (unsigned i = 0; i < n_; ++i)
        for (unsigned j = 0; j < n_; ++j)
          if (boundary.is_element(dofs[i]) || boundary.is_element(dofs[j])) m[i * n_ + j] = 0;
      for (double v : m) matrices_.push_back(float(v));
    }
    for (auto i : boundary)
      if (partitioner_->in_local_range(i)) constrained_.push_back(partitioner_->global_to_local(i));

    // Diagonal: element diagonals summed, 1 on the boundary; inverted for the smoother.
    diagonal_ = std::make_shared<DiagonalMatrix<VectorType>>();
    VectorType& d = diagonal_->get_vector();
    initialize_dof_vector(d);
    for (std::size_t c = 0; c < cell_matrix_.size(); ++c) {
      const float* m = &matrices_[std::size_t(cell_matrix_[c]) * n_ * n_];
      for (unsigned i = 0; i < n_; ++i) d.local_element(cell_dofs_[c * n_ + i]) += m[i * n_ + i];
    }
    d.compress(VectorOperation::add);
    for (auto i : constrained_) d.local_element(i) = 1;
    for (unsigned i = 0; i < d.locally_owned_size(); ++i)
      d.local_element(i) = d.local_element(i) > 0 ? 1.f / d.local_element(i) : 1.f;
  }

  std::shared_ptr<DiagonalMatrix<VectorType>> inverse_diagonal() const { return diagonal_; }
  const std::shared_ptr<const Utilities::MPI::Partitioner>& partitioner() const { return partitioner_; }
  void initialize_dof_vector(VectorType& v) const { v.reinit(partitioner_); }
  types::global_dof_index m() const { return partitioner_->size(); }
  types::global_dof_index n() const { return partitioner_->size(); }
  /// Only the diagonal (PreconditionChebyshev's fallback when no preconditioner is given).
  float el(types::global_dof_index i, types::global_dof_index) const { return 1.f / diagonal_->get_vector()(i); }
  std::size_t shapes() const { return matrices_.size() / (std::size_t(n_) * n_); }

  void vmult(VectorType& dst, const VectorType& src) const {
    dst = 0;
    vmult_add(dst, src);
  }
  void Tvmult(VectorType& dst, const VectorType& src) const { vmult(dst, src); }
  void Tvmult_add(VectorType& dst, const VectorType& src) const { vmult_add(dst, src); }
  void vmult_add(VectorType& dst, const VectorType& src) const {
    const bool ghosted = src.has_ghost_elements();
    if (!ghosted) src.update_ghost_values();
    if (dst.has_ghost_elements()) dst.zero_out_ghost_values();
    switch (n_) {  // fixed sizes unrolled: Q1/Q2 in 2D and 3D
      case 8: apply_cells<8>(dst, src); break;
      case 18: apply_cells<18>(dst, src); break;
      case 24: apply_cells<24>(dst, src); break;
      case 81: apply_cells<81>(dst, src); break;
      default: apply_cells<0>(dst, src);
    }
    dst.compress(VectorOperation::add);
    for (auto i : constrained_) dst.local_element(i) += src.local_element(i);
    if (!ghosted) src.zero_out_ghost_values();
  }

 private:
  template <unsigned N>
  void apply_cells(VectorType& dst, const VectorType& src) const {
    const unsigned n = N > 0 ? N : n_;
    float x[128], y[128];
    float* out = dst.begin();
    const float* in = src.begin();
    for (std::size_t c = 0; c < cell_matrix_.size(); ++c) {
      const unsigned* dofs = &cell_dofs_[c * n];
      const float* m = &matrices_[std::size_t(cell_matrix_[c]) * n * n];
      for (unsigned i = 0; i < n; ++i) x[i] = in[dofs[i]];
      // y = sum_j x_j m(:, j) (m is symmetric): each step an axpy over a contiguous row, which the
      // compiler vectorises; the dot-product form (a float reduction) it may not reorder.
      for (unsigned i = 0; i < n; ++i) y[i] = 0;
      for (unsigned j = 0; j < n; ++j) {
        const float xj = x[j];
        const float* row = m + j * n;
        for (unsigned i = 0; i < n; ++i) y[i] += row[i] * xj;
      }
      for (unsigned i = 0; i < n; ++i) out[dofs[i]] += y[i];
    }
  }

  unsigned n_ = 0;
  std::shared_ptr<const Utilities::MPI::Partitioner> partitioner_;
  std::vector<unsigned> cell_dofs_, cell_matrix_, constrained_;
  std::vector<float> matrices_;
  std::shared_ptr<DiagonalMatrix<VectorType>> diagonal_;
};

/// Coarse level: KLU on the assembled level-0 matrix (or one ML cycle when it is large); the
/// boundary DoFs of the level stay zero.
template <int dim, int degree>
class CoarseSolver : public MGCoarseGridBase<LinearAlgebra::distributed::Vector<float>> {
 public:
  using LevelVector = LinearAlgebra::distributed::Vector<float>;

  CoarseSolver(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const MGConstrainedDoFs& mg_constrained,
               const MgSettings& s, std::string& name)
      : control_(1, 0) {
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

    if (direct_is_fast(double(dof.n_dofs(0)), dim, s.direct_limit)) {
      direct_ = std::make_unique<TrilinosWrappers::SolverDirect>(
          control_, TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
      direct_->initialize(matrix_);
      name = "KLU";
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

  void operator()(const unsigned int, LevelVector& dst, const LevelVector& src) const override {
    for (unsigned i = 0; i < b_.locally_owned_size(); ++i) b_.local_element(i) = src.local_element(i);
    for (auto i : boundary_)
      if (b_.in_local_range(i)) b_(i) = 0;
    if (direct_)
      direct_->solve(x_, b_);
    else
      amg_->vmult(x_, b_);
    for (auto i : boundary_)
      if (x_.in_local_range(i)) x_(i) = 0;
    for (unsigned i = 0; i < x_.locally_owned_size(); ++i) dst.local_element(i) = float(x_.local_element(i));
  }

 private:
  SolverControl control_;
  TrilinosWrappers::SparseMatrix matrix_;
  std::unique_ptr<TrilinosWrappers::SolverDirect> direct_;
  std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_;
  IndexSet boundary_;
  std::vector<double> modes_;  // ML keeps a pointer
  mutable LinearAlgebra::distributed::Vector<double> b_, x_;
};

template <int dim, int degree>
MgOutcome solve_mg_degree(const Mapping<dim>& mapping, DoFHandler<dim>& dof, const AffineConstraints<double>& constraints,
                          const MgBoundaries& boundaries, const TrilinosWrappers::MPI::Vector& rhs,
                          TrilinosWrappers::MPI::Vector& solution, const MgSettings& s,
                          const std::function<void(const char*)>& profile) {
  using SystemOperator = ElasticOperator<dim, degree, double>;
  using LevelOperator = CellMatrixOperator<dim>;
  using VectorType = LinearAlgebra::distributed::Vector<double>;
  using LevelVector = LinearAlgebra::distributed::Vector<float>;

  profile("matrix-free operator");
  // The active level: homogeneous version of the constraints.
  AffineConstraints<double> homogeneous;
  {
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof, relevant);
    homogeneous.reinit(relevant);
    for (const auto& line : constraints.get_lines()) {
      homogeneous.add_line(line.index);
      homogeneous.add_entries(line.index, line.entries);
    }
    homogeneous.close();
  }
  SystemOperator system;
  {
    typename MatrixFree<dim, double>::AdditionalData data;
    data.tasks_parallel_scheme = MatrixFree<dim, double>::AdditionalData::none;
    data.mapping_update_flags = update_gradients | update_JxW_values;
    auto mf = std::make_shared<MatrixFree<dim, double>>();
    mf->reinit(mapping, dof, homogeneous, QGauss<1>(degree + 1), data);
    system.initialize(mf);
    system.set_coefficients(s.lambda, s.mu);
  }

  // The levels.
  profile("multigrid levels");
  dof.distribute_mg_dofs();
  MGConstrainedDoFs mg_constrained;
  mg_constrained.initialize(dof);
  for (const auto& [ids, mask] : boundaries) mg_constrained.make_zero_boundary_constraints(dof, ids, mask);
  const unsigned n_levels = dof.get_triangulation().n_global_levels();
  MGLevelObject<LevelOperator> levels(0, n_levels - 1);
  std::vector<std::shared_ptr<const Utilities::MPI::Partitioner>> partitioners(n_levels);
  for (unsigned level = 0; level < n_levels; ++level) {
    levels[level].build(mapping, dof, mg_constrained, level, s.lambda, s.mu);
    partitioners[level] = levels[level].partitioner();
  }
  MGTransferMatrixFree<dim, float> transfer(mg_constrained);
  transfer.build(dof, partitioners);

  profile("smoothers + coarse solver");
  using Smoother = PreconditionChebyshev<LevelOperator, LevelVector>;
  mg::SmootherRelaxation<Smoother, LevelVector> smoother;
  MGLevelObject<typename Smoother::AdditionalData> smoother_data(0, n_levels - 1);
  for (unsigned level = 0; level < n_levels; ++level) {
    smoother_data[level].smoothing_range = 15.;
    smoother_data[level].degree = unsigned(s.smoother_degree);
    smoother_data[level].eig_cg_n_iterations = 12;
    smoother_data[level].preconditioner = levels[level].inverse_diagonal();
  }
  smoother.initialize(levels, smoother_data);
  std::string coarse_name;
  CoarseSolver<dim, degree> coarse(mapping, dof, mg_constrained, s, coarse_name);
  mg::Matrix<LevelVector> mg_matrix(levels);
  Multigrid<LevelVector> mg(mg_matrix, coarse, transfer, smoother, smoother);
  PreconditionMG<dim, LevelVector, MGTransferMatrixFree<dim, float>> preconditioner(dof, mg, transfer);

  profile("CG");
  VectorType b, x;
  system.initialize_dof_vector(b);
  system.initialize_dof_vector(x);
  for (auto i : b.get_partitioner()->locally_owned_range()) b(i) = rhs(i);
  homogeneous.set_zero(b);
  const double b_norm = rhs.l2_norm();
  SolverControl control(s.max_iterations, s.tolerance * b_norm, false, false);
  SolverCG<VectorType> cg(control);
  cg.solve(system, x, b, preconditioner);
  profile(nullptr);

  MgOutcome out;
  out.iterations = int(control.last_step());
  for (unsigned level = 0; level < n_levels; ++level) out.matrices_per_level.push_back(levels[level].shapes());
  {
    VectorType r;
    r.reinit(x);
    system.vmult(r, x);
    r -= b;
    homogeneous.set_zero(r);
    out.residual = b_norm == 0 ? 0.0 : r.l2_norm() / b_norm;
  }
  for (auto i : x.get_partitioner()->locally_owned_range()) solution(i) = x(i);
  solution.compress(VectorOperation::insert);
  out.solver = "cg+gmg (matrix-free, " + std::to_string(n_levels) + " levels, Chebyshev " +
               std::to_string(s.smoother_degree) + ", coarse " + coarse_name + ")";
  return out;
}

}  // namespace

template <int dim>
MgOutcome solve_mg(const Mapping<dim>& mapping, DoFHandler<dim>& dof, const AffineConstraints<double>& constraints,
                   const MgBoundaries& boundaries, const TrilinosWrappers::MPI::Vector& rhs,
                   TrilinosWrappers::MPI::Vector& solution, const MgSettings& s,
                   const std::function<void(const char*)>& profile) {
  if (dof.get_fe().degree == 1)
    return solve_mg_degree<dim, 1>(mapping, dof, constraints, boundaries, rhs, solution, s, profile);
  return solve_mg_degree<dim, 2>(mapping, dof, constraints, boundaries, rhs, solution, s, profile);
}

template MgOutcome solve_mg<2>(const Mapping<2>&, DoFHandler<2>&, const AffineConstraints<double>&, const MgBoundaries&,
                               const TrilinosWrappers::MPI::Vector&, TrilinosWrappers::MPI::Vector&, const MgSettings&,
                               const std::function<void(const char*)>&);
template MgOutcome solve_mg<3>(const Mapping<3>&, DoFHandler<3>&, const AffineConstraints<double>&, const MgBoundaries&,
                               const TrilinosWrappers::MPI::Vector&, TrilinosWrappers::MPI::Vector&, const MgSettings&,
                               const std::function<void(const char*)>&);

}  // namespace fem_reference
