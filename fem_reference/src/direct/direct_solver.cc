// The sparse direct solver (direct_solver.h): CHOLMOD on one rank, Amesos KLU under MPI.
#include "direct/direct_solver.h"

#include <deal.II/base/mpi.h>

#include <Epetra_CrsMatrix.h>
#include <Epetra_Map.h>
#include <cholmod.h>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fem_reference {

using namespace dealii;

struct DirectSolver::Cholmod {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  Cholmod() {
    cholmod_l_start(&common);
    common.print = 0;  // errors become exceptions (status), not printed
  }
  ~Cholmod() {
    if (factor) cholmod_l_free_factor(&factor, &common);
    cholmod_l_finish(&common);
  }
  void check(const char* what) const {
    if (common.status == CHOLMOD_NOT_POSDEF)
      throw std::runtime_error("the stiffness matrix is not positive definite (CHOLMOD " + std::string(what) +
                             "): check the supports");
    if (common.status < CHOLMOD_OK)
      throw std::runtime_error("CHOLMOD " + std::string(what) + " failed (status " + std::to_string(common.status) + ")");
  }
};

namespace {

/// The upper triangle (row <= column) of a one-rank Epetra matrix in compressed columns: the
/// matrix is symmetric, so row j's entries up to the diagonal are column j's.
cholmod_sparse* upper_triangle(const Epetra_CrsMatrix& a, cholmod_common& common) {
  const long n = a.NumMyRows();
  long nnz = 0;
  for (long r = 0; r < n; ++r) nnz += a.NumMyEntries(int(r));
  cholmod_sparse* s = cholmod_l_allocate_sparse(n, n, nnz, false, true, 1, CHOLMOD_REAL, &common);
  if (!s) return nullptr;
  auto* p = static_cast<SuiteSparse_long*>(s->p);
  auto* i = static_cast<SuiteSparse_long*>(s->i);
  auto* x = static_cast<double*>(s->x);
  long k = 0;
  for (long r = 0; r < n; ++r) {
    p[r] = k;
    const long row = a.RowMap().GID(int(r));
    int count = 0;
    double* values = nullptr;
    int* columns = nullptr;
    a.ExtractMyRowView(int(r), count, values, columns);
    for (int e = 0; e < count; ++e) {
      const long column = a.ColMap().GID(columns[e]);
      if (column > row) continue;
      i[k] = column;
      x[k++] = values[e];
    }
  }
  p[n] = k;
  return s;
}

}  // namespace

DirectSolver::DirectSolver(const TrilinosWrappers::SparseMatrix& matrix) {
  if (Utilities::MPI::n_mpi_processes(matrix.get_mpi_communicator()) > 1) {
    klu_ = std::make_unique<TrilinosWrappers::SolverDirect>(
        control_, TrilinosWrappers::SolverDirect::AdditionalData(false, "Amesos_Klu"));
    klu_->initialize(matrix);
    return;
  }
  cholmod_ = std::make_unique<Cholmod>();
  cholmod_common& c = cholmod_->common;
  cholmod_sparse* a = upper_triangle(matrix.trilinos_matrix(), c);
  cholmod_->check("allocation");
  cholmod_->factor = cholmod_l_analyze(a, &c);
  if (cholmod_->factor) cholmod_l_factorize(a, cholmod_->factor, &c);
  cholmod_l_free_sparse(&a, &c);
  cholmod_->check("factorisation");
}

DirectSolver::~DirectSolver() = default;

void DirectSolver::solve_serial(double* x, const double* b) const {
  cholmod_common& c = cholmod_->common;
  const long n = long(cholmod_->factor->n);
  cholmod_dense* rhs = cholmod_l_allocate_dense(n, 1, n, CHOLMOD_REAL, &c);
  cholmod_->check("allocation");
  std::copy(b, b + n, static_cast<double*>(rhs->x));
  cholmod_dense* solution = cholmod_l_solve(CHOLMOD_A, cholmod_->factor, rhs, &c);
  cholmod_l_free_dense(&rhs, &c);
  cholmod_->check("solve");
  const double* u = static_cast<const double*>(solution->x);
  std::copy(u, u + n, x);
  cholmod_l_free_dense(&solution, &c);
}

}  // namespace fem_reference
