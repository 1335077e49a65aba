#pragma once
// The sparse direct solver of the FEM reference (private header; deal.II types): on one rank a
// Cholesky factorisation by CHOLMOD (SuiteSparse; supernodal where that pays, AMD or METIS
// ordering), under MPI Amesos KLU, which gathers the matrix on one rank. The solver of
// fem.solver = "direct" (and of "auto" where direct_is_fast) and the multigrid's coarse solve.
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <memory>
#include <string>

namespace fem_reference {

class DirectSolver {
 public:
  /// Factorises the symmetric positive definite `matrix` (throws workbench::Error if it is not).
  explicit DirectSolver(const dealii::TrilinosWrappers::SparseMatrix& matrix);
  ~DirectSolver();
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  /// x = K^-1 b for TrilinosWrappers::MPI::Vector or LinearAlgebra::distributed::Vector<double>.
  template <class Vector>
  void solve(Vector& x, const Vector& b) const {
    if (klu_)
      klu_->solve(x, b);
    else
      solve_serial(x.begin(), b.begin());
  }
  /// "CHOLMOD" or "KLU".
  std::string name() const { return klu_ ? "KLU" : "CHOLMOD"; }

 private:
  void solve_serial(double* x, const double* b) const;

  struct Cholmod;  // keeps cholmod.h out of this header
  std::unique_ptr<Cholmod> cholmod_;
  dealii::SolverControl control_{1, 0};
  std::unique_ptr<dealii::TrilinosWrappers::SolverDirect> klu_;
};

}  // namespace fem_reference
