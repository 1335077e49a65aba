#pragma once
// What the assembled problem (problem/) and the matrix-free multigrid (mg/) share: the one formula
// of the elastic bilinear form and the one rule for when a sparse direct solve is cheap.
#include <deal.II/base/tensor.h>

#include <cmath>

namespace fem_reference {

/// JxW-free entry (i, j) of the elastic element matrix: lambda div phi_i div phi_j +
/// mu (grad phi_i + grad phi_i^T) : grad phi_j for vector shape functions of components ci, cj with
/// scalar gradients gi, gj. The one formula of the assembled matrix and the multigrid levels.
template <int dim>
double elastic_entry(const dealii::Tensor<1, dim>& gi, const dealii::Tensor<1, dim>& gj, unsigned ci, unsigned cj,
                     double lambda, double mu) {
  double v = lambda * gi[ci] * gj[cj] + mu * gi[cj] * gj[ci];
  if (ci == cj) v += mu * (gi * gj);
  return v;
}

/// Whether a sparse direct factorisation of n DoFs is cheap: its expected work, by nested-dissection
/// estimates n^(3/2) in 2D and n^2 in 3D (separators of n^(1/2) and n^(2/3) DoFs), is at most that of
/// a 2D problem of `direct_limit` DoFs. In 3D that is direct_limit^(3/4) DoFs (1 682 for 20 000):
/// beyond it a 3D factorisation fills in so much that KLU takes tens of seconds where AMG takes a
/// fraction of one (docs/performance.md, the solver sweep). The automatic solver choice of the
/// problem and the multigrid's coarse solver.
inline bool direct_is_fast(double n_dofs, int dim, long direct_limit) {
  const double limit = double(direct_limit);
  return dim == 2 ? n_dofs <= limit : n_dofs * n_dofs <= limit * std::sqrt(limit);
}

}  // namespace fem_reference
