#pragma once
// The FEM reference's MPI runtime, for programs and tests (no MPI or deal.II in this header): the
// start-up settings of a one-process run, this process's rank, and the collective steps by which the
// ranks agree (the command line's staged output folder, an error on any rank ending every rank).
// The library starts MPI itself when first needed and finalises it at exit.
//
//   int main() {
//     fem_reference::configure_singleton_mpi();   // first: it sets the environment
//     ...
//     fem_reference::mpi_collective([&] { if (fem_reference::mpi_rank() == 0) make_folder(); });
//   }
#include <functional>
#include <string>

namespace fem_reference {

/// For a run that mpirun or srun did not start (one process): sets OpenMPI's environment so that
/// MPI starts up in 0.02 s instead of 0.27 s: the ob1 point-to-point layer instead of probing UCX,
/// no UCX one-sided component (both serve networks one process does not use) and no orted helper
/// for the singleton. A variable already set is kept; under mpirun or srun nothing changes. Call it
/// first in main(), before any thread starts (setenv is not safe beside another thread's getenv).
void configure_singleton_mpi();

/// MPI rank of this process and the number of ranks (1 without mpirun); these initialise MPI
/// (finalised at exit) if the program has not.
int mpi_rank();
int mpi_size();
/// Waits for every rank.
void mpi_barrier();
/// Broadcasts a string from rank 0.
std::string mpi_broadcast(const std::string& text);
/// Runs `step` on every rank (collective: every rank calls it); if it throws on any rank, every rank
/// throws the same workbench::Error (the message of the lowest failing rank), so no rank is left
/// waiting in a later collective. For steps that may fail on one rank only (files, folders).
void mpi_collective(const std::function<void()>& step);

}  // namespace fem_reference
