// The elasticity operator from stored element matrices (private header; deal.II types): the
// multigrid's level operators and its outer CG's operator (mg_solver.cc), and the operator
// benchmark (bench/fem/bench_operator.cc).
#pragma once

#include "elasticity.h"

#include <deal.II/base/aligned_vector.h>
#include <deal.II/base/index_set.h>
#include <deal.II/base/partitioner.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/diagonal_matrix.h>
#include <deal.II/lac/la_parallel_vector.h>
#include <deal.II/multigrid/mg_constrained_dofs.h>

#include <immintrin.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <type_traits>
#include <vector>

namespace fem_reference {

using namespace dealii;  // NOLINT: a private header of deal.II code, included by its two users only

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
                dof.mg_cell_iterators_on_level(level), lambda, mu, [level](const auto& cell, auto& dofs, bool vertices) {
                  if (!cell->is_locally_owned_on_level()) return false;
                  if (vertices)  // Q1: the DoFs are the vertices' (3D get_mg_dof_indices walks lines and faces too)
                    for (unsigned v = 0, i = 0; v < cell->n_vertices(); ++v)
                      for (int c = 0; c < dim; ++c, ++i) dofs[i] = cell->mg_vertex_dof_index(int(level), v, unsigned(c));
                  else
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
                [](const auto& cell, auto& dofs, bool vertices) {
                  if (!cell->is_locally_owned()) return false;
                  if (vertices)
                    for (unsigned v = 0, i = 0; v < cell->n_vertices(); ++v)
                      for (int c = 0; c < dim; ++c, ++i) dofs[i] = cell->vertex_dof_index(v, unsigned(c));
                  else
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

  static bool owned_cell(const typename DoFHandler<dim>::level_cell_iterator& cell) {
    return cell->is_locally_owned_on_level();
  }
  static bool owned_cell(const typename DoFHandler<dim>::active_cell_iterator& cell) { return cell->is_locally_owned(); }

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
    std::vector<long long> key, last_key;
    unsigned last_shape = 0;
    std::vector<Tensor<1, dim>> grads(n_);
    std::vector<unsigned> local(n_);
    // Q1 (the DoFs those of the vertices, vertex by vertex, component by component): the indices
    // read per vertex, checked against get_(mg_)dof_indices on the first cell.
    bool vertices = fe.n_dofs_per_cell() == fe.n_dofs_per_vertex() * GeometryInfo<dim>::vertices_per_cell &&
                    fe.n_dofs_per_vertex() == unsigned(dim);
    bool checked = !vertices;
    std::vector<types::global_dof_index> check(n_);
    Point<dim> vertex[GeometryInfo<dim>::vertices_per_cell];
    // Sized once: grown by doubling, the stores into fresh pages and the copies were half of this loop.
    std::size_t n_cells = 0;
    for (const auto& cell : cells) n_cells += owned_cell(cell);
    cell_dofs_.reserve(n_cells * n_);
    cell_matrix_.reserve(n_cells);
    for (const auto& cell : cells) {
      if (!cell_dofs(cell, dofs, vertices)) continue;
      if (!checked) {
        cell_dofs(cell, check, false);
        vertices = check == dofs;
        dofs = check;
        checked = true;
      }
      const unsigned n_vertices = cell->n_vertices();
      for (unsigned v = 0; v < n_vertices; ++v) vertex[v] = cell->vertex(v);
      double scale = 0;
      for (unsigned v = 1; v < n_vertices; ++v)
        for (int a = 0; a < dim; ++a) scale = std::max(scale, std::abs(vertex[v][a] - vertex[0][a]));
      int exponent = 0;
      const double mantissa = std::frexp(scale, &exponent);
      key.assign({exponent, std::llround(mantissa * quanta)});
      for (unsigned v = 1; v < n_vertices; ++v)
        for (int a = 0; a < dim; ++a) key.push_back(std::llround((vertex[v][a] - vertex[0][a]) / scale * quanta));
      for (unsigned i = 0; i < n_; ++i) {
        local[i] = partitioner_->global_to_local(dofs[i]);
        key.push_back(is_constrained[local[i]]);
        cell_dofs_.push_back(local[i]);
      }
      // Neighbouring cells mostly share a shape: the last one's first, then the map (no node made
      // unless the shape is new).
      if (!last_key.empty() && key == last_key) {
        cell_matrix_.push_back(last_shape);
        continue;
      }
      auto it = shapes.find(key);
      const bool added = it == shapes.end();
      if (added) it = shapes.emplace(key, unsigned(shapes.size())).first;
      cell_matrix_.push_back(it->second);
      last_key = key;
      last_shape = it->second;
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
  /// The product in plain C++ (N = 0: any size), which the compiler vectorises for the target.
  template <unsigned N>
  void apply_cells(VectorType& dst, const VectorType& src) const {
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

}  // namespace fem_reference
