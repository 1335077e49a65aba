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

#include <immintrin.h>

#include <cstdlib>
#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <tuple>

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

/// The elasticity operator from stored element matrices, applied cell by cell: gather, small dense
/// product, scatter. On the multigrid levels in single precision, on the active mesh in double (the
/// outer CG's operator). Deal.II's MatrixFree runs without SIMD here (Debian's deal.II is configured
/// with vectorization width 0), where sum factorisation on Q1/Q2 cells is slower than this and its
/// set-up alone costs as much as the V-cycles' operators. Cells of the same shape share one matrix,
/// so a structured mesh stores a handful: the shape is keyed to 2^-22 of the cell size in single
/// precision, to 2^-40 in double (below the rounding noise of gmsh's coordinates: no cell gets
/// another's matrix). Constrained DoFs (the level's boundary, or the active mesh's homogeneous
/// constraints) get identity rows and columns.
template <int dim, typename Number>
class CellMatrixOperator : public Subscriptor {
 public:
  using VectorType = LinearAlgebra::distributed::Vector<Number>;

  /// A level's operator.
  void build(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const MGConstrainedDoFs& mg_constrained,
             unsigned level, double lambda, double mu) {
    IndexSet relevant;
    DoFTools::extract_locally_relevant_level_dofs(dof, level, relevant);
    build_cells(mapping, dof, dof.locally_owned_mg_dofs(level), relevant, mg_constrained.get_boundary_indices(level),
                dof.mg_cell_iterators_on_level(level), lambda, mu, [](const auto& cell, auto& dofs) {
                  if (!cell->is_locally_owned_on_level()) return false;
                  cell->get_mg_dof_indices(dofs);
                  return true;
                });
  }

  /// The active mesh's operator; `constrained`: the DoFs of homogeneous constraint lines without
  /// entries (no hanging nodes: the meshes are refined globally).
  void build(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const IndexSet& constrained, double lambda,
             double mu) {
    IndexSet relevant;
    DoFTools::extract_locally_relevant_dofs(dof, relevant);
    build_cells(mapping, dof, dof.locally_owned_dofs(), relevant, constrained, dof.active_cell_iterators(), lambda, mu,
                [](const auto& cell, auto& dofs) {
                  if (!cell->is_locally_owned()) return false;
                  cell->get_dof_indices(dofs);
                  return true;
                });
  }

  std::shared_ptr<DiagonalMatrix<VectorType>> inverse_diagonal() const { return diagonal_; }
  const std::shared_ptr<const Utilities::MPI::Partitioner>& partitioner() const { return partitioner_; }
  void initialize_dof_vector(VectorType& v) const { v.reinit(partitioner_); }
  types::global_dof_index m() const { return partitioner_->size(); }
  types::global_dof_index n() const { return partitioner_->size(); }
  /// Only the diagonal (PreconditionChebyshev's fallback when no preconditioner is given).
  Number el(types::global_dof_index i, types::global_dof_index) const { return Number(1) / diagonal_->get_vector()(i); }
  std::size_t shapes() const { return matrices_.size() / (std::size_t(n_) * stride_); }

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
    // With AVX2 and FMA where the processor has them (the build targets plain x86-64, whose SSE2
    // needs four instructions for one 8-wide float FMA).
    static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    switch (n_) {  // fixed sizes unrolled: Q1/Q2 in 2D and 3D
      case 8: avx2 ? apply_cells_avx2<8>(dst, src) : apply_cells<8>(dst, src); break;
      case 18: avx2 ? apply_cells_avx2<18>(dst, src) : apply_cells<18>(dst, src); break;
      case 24: avx2 ? apply_cells_avx2<24>(dst, src) : apply_cells<24>(dst, src); break;
      case 81: avx2 ? apply_cells_avx2<81>(dst, src) : apply_cells<81>(dst, src); break;
      default: apply_cells<0>(dst, src);
    }
    dst.compress(VectorOperation::add);
    for (auto i : constrained_) dst.local_element(i) += src.local_element(i);
    if (!ghosted) src.zero_out_ghost_values();
  }

 private:
  // Matrix rows padded to whole SIMD registers (32 bytes), so that the product is register-wide
  // multiply-adds of a broadcast x_j with matrix row j (the matrix is symmetric).
  static constexpr unsigned kLanes = 32 / sizeof(Number);
  static constexpr unsigned padded(unsigned n) { return (n + kLanes - 1) / kLanes * kLanes; }

  template <typename Cells, typename CellDofs>
  void build_cells(const Mapping<dim>& mapping, const DoFHandler<dim>& dof, const IndexSet& owned,
                   const IndexSet& relevant, const IndexSet& constrained, const Cells& cells, double lambda, double mu,
                   const CellDofs& cell_dofs) {
    const auto& fe = dof.get_fe();
    n_ = fe.n_dofs_per_cell();
    stride_ = padded(n_);
    partitioner_ = std::make_shared<Utilities::MPI::Partitioner>(owned, relevant, dof.get_communicator());
    // Constrained flags by local index (IndexSet::is_element per DoF and cell costs a search).
    std::vector<char> is_constrained(partitioner_->locally_owned_size() + partitioner_->n_ghost_indices(), 0);
    for (auto i : constrained)
      if (relevant.is_element(i)) is_constrained[partitioner_->global_to_local(i)] = 1;
    QGauss<dim> quadrature(fe.degree + 1);
    FEValues<dim> fe_values(mapping, fe, quadrature, update_gradients | update_JxW_values);
    std::vector<types::global_dof_index> dofs(n_);
    std::vector<unsigned> comp(n_);
    for (unsigned i = 0; i < n_; ++i) comp[i] = fe.system_to_component_index(i).first;
    const double quanta = std::is_same_v<Number, float> ? 4194304.0 : 1099511627776.0;  // 2^22, 2^40
    std::map<std::vector<long long>, unsigned> shapes;  // shape (vertices - vertex 0) and constrained pattern
    std::vector<long long> key;
    std::vector<Tensor<1, dim>> grads(n_);
    std::vector<unsigned> local(n_);
    for (const auto& cell : cells) {
      if (!cell_dofs(cell, dofs)) continue;
      double scale = 0;
      for (unsigned v = 1; v < cell->n_vertices(); ++v)
        for (int a = 0; a < dim; ++a) scale = std::max(scale, std::abs(cell->vertex(v)[a] - cell->vertex(0)[a]));
      int exponent = 0;
      const double mantissa = std::frexp(scale, &exponent);
      key.assign({exponent, std::llround(mantissa * quanta)});
      for (unsigned v = 1; v < cell->n_vertices(); ++v)
        for (int a = 0; a < dim; ++a) key.push_back(std::llround((cell->vertex(v)[a] - cell->vertex(0)[a]) / scale * quanta));
      for (unsigned i = 0; i < n_; ++i) {
        local[i] = partitioner_->global_to_local(dofs[i]);
        key.push_back(is_constrained[local[i]]);
        cell_dofs_.push_back(local[i]);
      }
      auto [it, added] = shapes.emplace(key, unsigned(shapes.size()));
      cell_matrix_.push_back(it->second);
      if (!added) continue;
      fe_values.reinit(cell);
      std::vector<double> m(std::size_t(n_) * stride_, 0.0);
      for (unsigned q = 0; q < quadrature.size(); ++q) {
        const double JxW = fe_values.JxW(q);
        for (unsigned i = 0; i < n_; ++i) grads[i] = fe_values.shape_grad(i, q);
        for (unsigned i = 0; i < n_; ++i)
          for (unsigned j = 0; j < n_; ++j)
            m[i * stride_ + j] += elastic_entry<dim>(grads[i], grads[j], comp[i], comp[j], lambda, mu) * JxW;
      }
      for (unsigned i = 0; i < n_; ++i)
        for (unsigned j = 0; j < n_; ++j)
          if (is_constrained[local[i]] || is_constrained[local[j]]) m[i * stride_ + j] = 0;
      for (double v : m) matrices_.push_back(Number(v));
    }
    for (auto i : constrained)
      if (partitioner_->in_local_range(i)) constrained_.push_back(partitioner_->global_to_local(i));

    // Diagonal: element diagonals summed, 1 on the constrained DoFs; inverted for the smoother.
    diagonal_ = std::make_shared<DiagonalMatrix<VectorType>>();
    VectorType& d = diagonal_->get_vector();
    initialize_dof_vector(d);
    for (std::size_t c = 0; c < cell_matrix_.size(); ++c) {
      const Number* m = &matrices_[std::size_t(cell_matrix_[c]) * n_ * stride_];
      for (unsigned i = 0; i < n_; ++i) d.local_element(cell_dofs_[c * n_ + i]) += m[i * stride_ + i];
    }
    d.compress(VectorOperation::add);
    for (auto i : constrained_) d.local_element(i) = 1;
    for (unsigned i = 0; i < d.locally_owned_size(); ++i)
      d.local_element(i) = d.local_element(i) > 0 ? Number(1) / d.local_element(i) : Number(1);
  }

  template <unsigned N>
  void apply_cells(VectorType& dst, const VectorType& src) const {
    apply_cells_inline<N>(dst, src);
  }
  /// The same product in AVX2 intrinsics: per matrix row one broadcast x_j and one FMA per register
  /// (the compiler, left to itself, builds x in a register by inserts and permutes the matrix).
  template <unsigned N>
  __attribute__((target("avx2,fma"))) void apply_cells_avx2(VectorType& dst, const VectorType& src) const {
    constexpr unsigned P = padded(N), R = P / kLanes;
    alignas(32) Number y[P];
    Number* out = dst.begin();
    const Number* in = src.begin();
    for (std::size_t c = 0; c < cell_matrix_.size(); ++c) {
      const unsigned* dofs = &cell_dofs_[c * N];
      const Number* m = &matrices_[std::size_t(cell_matrix_[c]) * N * P];
      if constexpr (std::is_same_v<Number, float>) {
        __m256 acc[R];
        for (unsigned r = 0; r < R; ++r) acc[r] = _mm256_setzero_ps();
        for (unsigned j = 0; j < N; ++j) {
          const __m256 xj = _mm256_set1_ps(in[dofs[j]]);
          for (unsigned r = 0; r < R; ++r) acc[r] = _mm256_fmadd_ps(_mm256_loadu_ps(m + j * P + r * kLanes), xj, acc[r]);
        }
        for (unsigned r = 0; r < R; ++r) _mm256_store_ps(y + r * kLanes, acc[r]);
      } else {
        __m256d acc[R];
        for (unsigned r = 0; r < R; ++r) acc[r] = _mm256_setzero_pd();
        for (unsigned j = 0; j < N; ++j) {
          const __m256d xj = _mm256_set1_pd(in[dofs[j]]);
          for (unsigned r = 0; r < R; ++r) acc[r] = _mm256_fmadd_pd(_mm256_loadu_pd(m + j * P + r * kLanes), xj, acc[r]);
        }
        for (unsigned r = 0; r < R; ++r) _mm256_store_pd(y + r * kLanes, acc[r]);
      }
      for (unsigned i = 0; i < N; ++i) out[dofs[i]] += y[i];
    }
  }
  template <unsigned N>
  __attribute__((always_inline)) inline void apply_cells_inline(VectorType& dst, const VectorType& src) const {
    const unsigned n = N > 0 ? N : n_;
    constexpr unsigned P = padded(N > 0 ? N : 1);
    const unsigned stride = N > 0 ? P : stride_;
    alignas(32) Number y[N > 0 ? P : 256];
    Number* out = dst.begin();
    const Number* in = src.begin();
    for (std::size_t c = 0; c < cell_matrix_.size(); ++c) {
      const unsigned* dofs = &cell_dofs_[c * n];
      const Number* m = &matrices_[std::size_t(cell_matrix_[c]) * n * stride];
      // y = sum_j x_j m(j, :): each step a multiply-add of a broadcast x_j over a padded row, which
      // the compiler turns into whole-register FMAs (the dot-product form, a reduction, it may not).
      for (unsigned i = 0; i < stride; ++i) y[i] = 0;
      for (unsigned j = 0; j < n; ++j) {
        const Number xj = in[dofs[j]];
        const Number* row = m + j * stride;
        for (unsigned i = 0; i < stride; ++i) y[i] += row[i] * xj;
      }
      for (unsigned i = 0; i < n; ++i) out[dofs[i]] += y[i];
    }
  }

  unsigned n_ = 0, stride_ = 0;
  std::shared_ptr<const Utilities::MPI::Partitioner> partitioner_;
  std::vector<unsigned> cell_dofs_, cell_matrix_, constrained_;
  AlignedVector<Number> matrices_;
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

  /// The coarse level's own problem K0 x = b to `tolerance` (relative residual): KLU, or CG with the
  /// ML preconditioner. Returns the CG iterations (0 for KLU) and the relative residual.
  std::pair<int, double> solve(LinearAlgebra::distributed::Vector<double>& x,
                               const LinearAlgebra::distributed::Vector<double>& b, double tolerance,
                               int max_iterations) const {
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
  {
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
  MGLevelObject<typename Smoother::AdditionalData> smoother_data(0, n_levels - 1);
  for (unsigned level = 0; level < n_levels; ++level) {
    smoother_data[level].smoothing_range = 15.;
    smoother_data[level].degree = unsigned(s.smoother_degree);
    smoother_data[level].eig_cg_n_iterations = 12;
    smoother_data[level].preconditioner = levels[level].inverse_diagonal();
  }
  smoother.initialize(levels, smoother_data);
  profile("coarse solver");
  std::string coarse_name;
  CoarseSolver<dim, degree> coarse(mapping, dof, mg_constrained, s, coarse_name);
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
    VectorType r;
    r.reinit(x);
    system.vmult(r, x);
    r -= b;
    homogeneous.set_zero(r);
    const double start = r.l2_norm();
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
