#pragma once
// The MPI runtime inside the library (runtime.cc): what the public fem_reference/mpi.h offers, and
// the start-up the solver calls before it builds a distributed mesh.
#include <fem_reference/mpi.h>

namespace fem_reference {

/// Sets deal.II's exceptions to throw quietly (no abort, no stack trace) and, unless the program
/// did, initialises MPI (MPI_THREAD_SERIALIZED), p4est's sc library and a one-thread limit, with
/// MPI finalised at exit. mpi_rank, mpi_size and mpi_barrier call it first, solve_on_mesh before it
/// builds the problem.
void ensure_mpi();

/// Transparent huge pages for the FEM's allocations (Linux with glibc; runtime.cc says how and why):
/// ensure_mpi calls it, before the mesh is built (every solve starts there); once per process.
void huge_page_heap();

}  // namespace fem_reference
