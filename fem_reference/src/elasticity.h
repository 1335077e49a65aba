#pragma once
// What the assembled problem (problem/) and the matrix-free multigrid (mg/) share: the one formula
// of the elastic bilinear form and the rules for when a sparse direct solve is cheap.
#include <deal.II/base/tensor.h>

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

/// Whether `auto` factorises a whole problem of n DoFs on a body `slenderness` times longer than
/// wide (plain_mesh.h): up to fem.direct_limit DoFs times the slenderness, in 2D and 3D alike.
/// Measured (docs/performance.md, issue 38), the factorisation (CHOLMOD) breaks even with CG + ML
/// (Q1) and the p-multigrid (Q2) at 1 800 to 2 200 DoFs on squares and cubes. A slender body is a
/// row of such squares (cubes), each factorised at the cost of one, against iterations that grow
/// with its ill-conditioning in bending: a 500 x 2 mm strip of 20 010 DoFs factorises in 0.05 s,
/// where the p-multigrid takes 0.16 s and ML 0.25 s.
inline bool direct_is_fast(double n_dofs, double slenderness, long direct_limit) {
  return n_dofs <= slenderness * double(direct_limit);
}

/// Whether a multigrid's assembled coarse level of n DoFs is factorised (else one ML cycle): in 2D up
/// to 10 x direct_limit (20 000), since its one factorisation serves every V-cycle of a problem at
/// least 4 times larger (the 1e6-DoF plate's coarse mesh, 15 842 DoFs, stays factorised: 6
/// iterations, docs/performance.md); in 3D, whose fill grows as n^2 (n^(3/2) in 2D), up to
/// direct_limit.
inline bool coarse_direct_is_fast(double n_dofs, int dim, long direct_limit) {
  return n_dofs <= (dim == 2 ? 10.0 : 1.0) * double(direct_limit);
}

}  // namespace fem_reference
